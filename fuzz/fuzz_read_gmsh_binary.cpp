// libFuzzer target: the binary Gmsh reader. The first byte chooses the
// format line (bit 0: 2.2 or 4.1) and the byte order of the marker (bit 1:
// little- or big-endian); the other bytes are the file after $EndMeshFormat,
// so that every input reaches the binary sections at once.
#include "fuzz_reader_common.h"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size == 0)
    return 0;
  std::string file = (data[0] & 1) ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n2.2 1 8\n";
  file += (data[0] & 2) ? std::string("\0\0\0\1", 4) : std::string("\1\0\0\0", 4);
  file += "\n$EndMeshFormat\n";
  file.append(reinterpret_cast<const char*>(data + 1), size - 1);
  return spring_motion_fuzz::run_reader(reinterpret_cast<const std::uint8_t*>(file.data()), file.size(),
                                        [](std::istream& in, const std::string& name) {
                                          return spring_motion::read_gmsh(in, name);
                                        });
}
