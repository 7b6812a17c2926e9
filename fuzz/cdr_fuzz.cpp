// CDR messages (logs/ros_messages.hpp): the first byte picks the type, the rest is the message.
#include <span>

#include "fuzz/fuzz_input.hpp"
#include "logs/ros_messages.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  if (size == 0) return 0;
  const std::span<const std::uint8_t> cdr(data + 1, size - 1);
  fuzz::Refusing([&] {
    switch (data[0] % 4) {
      case 0:
        logs::DecodeLaserScan(cdr);
        break;
      case 1:
        logs::DecodeOdometry(cdr);
        break;
      case 2:
        logs::DecodeTfMessage(cdr);
        break;
      default:
        logs::DecodePoseStamped(cdr);
        break;
    }
  });
  return 0;
}
