#pragma once
// The Markdown that retrace writes (comparison.md, report.md), as HTML for report.html: headings,
// paragraphs, `-` lists, pipe tables with their column alignment, fenced code, `code` and
// **bold**. Links stay text (the page refers to nothing outside itself); everything else is
// escaped, so any text is safe to pass.

#include <string>
#include <string_view>

namespace retrace::bench {

/// `markdown` as an HTML fragment; headings are moved down `heading_shift` levels (at most h6) so
/// that a file's `#` title sits below the page's own section headings.
std::string MarkdownToHtml(std::string_view markdown, int heading_shift = 2);

}  // namespace retrace::bench
