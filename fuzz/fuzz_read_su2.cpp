// libFuzzer target: the SU2 (.su2) reader on arbitrary bytes.
#include "fuzz_reader_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return spring_motion_fuzz::run_reader(data, size, [](std::istream& in, const std::string& name) {
    return spring_motion::read_su2(in, name);
  });
}
