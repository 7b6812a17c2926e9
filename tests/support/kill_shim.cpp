// LD_PRELOAD library for tests/cli/commit_kill_test.sh: counts the calls that rename or remove a
// path containing $RETRACE_KILL_MATCH (rename, renameat2, remove, unlink, unlinkat, rmdir), and
// kills the process with SIGKILL just before the call numbered $RETRACE_KILL_AT (from 1). With
// $RETRACE_KILL_COUNT_FILE set, the number of matching calls is written there at exit.

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

namespace {

long g_calls = 0;

bool Matches(const char* path) {  // path may be null (the second path of Count)
  const char* match = getenv("RETRACE_KILL_MATCH");
  return match != nullptr && path != nullptr && strstr(path, match) != nullptr;
}

void Count(const char* a, const char* b = nullptr) {
  if (!Matches(a) && !Matches(b)) return;
  ++g_calls;
  const char* at = getenv("RETRACE_KILL_AT");
  if (at != nullptr && atol(at) == g_calls) raise(SIGKILL);
}

template <typename F>
F Real(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}

__attribute__((destructor)) void WriteCount() {
  const char* file = getenv("RETRACE_KILL_COUNT_FILE");
  if (file == nullptr) return;
  FILE* f = Real<FILE* (*)(const char*, const char*)>("fopen")(file, "w");
  if (f == nullptr) return;
  fprintf(f, "%ld\n", g_calls);
  fclose(f);
}

}  // namespace

extern "C" {

int rename(const char* from, const char* to) {
  Count(from, to);
  return Real<int (*)(const char*, const char*)>("rename")(from, to);
}

int renameat2(int from_dir, const char* from, int to_dir, const char* to, unsigned int flags) {
  Count(from, to);
  return Real<int (*)(int, const char*, int, const char*, unsigned int)>("renameat2")(
      from_dir, from, to_dir, to, flags);
}

int remove(const char* path) {
  Count(path);
  return Real<int (*)(const char*)>("remove")(path);
}

int unlink(const char* path) {
  Count(path);
  return Real<int (*)(const char*)>("unlink")(path);
}

int unlinkat(int dir, const char* path, int flags) {
  // std::filesystem::remove_all removes a folder's entries relative to the folder's descriptor.
  char full[4096] = "";
  if (dir != AT_FDCWD && path[0] != '/') {
    char link[64];
    snprintf(link, sizeof link, "/proc/self/fd/%d", dir);
    const ssize_t n = readlink(link, full, sizeof full - 1);
    if (n > 0 && static_cast<size_t>(n) + strlen(path) + 2 < sizeof full) {
      full[n] = '/';
      strcpy(full + n + 1, path);
    } else {
      full[0] = '\0';
    }
  }
  Count(full[0] != '\0' ? full : path);
  return Real<int (*)(int, const char*, int)>("unlinkat")(dir, path, flags);
}

int rmdir(const char* path) {
  Count(path);
  return Real<int (*)(const char*)>("rmdir")(path);
}

}  // extern "C"
