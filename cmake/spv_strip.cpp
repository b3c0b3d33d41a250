// A build tool: spv_strip IN OUT copies the SPIR-V module IN to OUT without its source text and
// line information (OpSource, OpSourceContinued, OpSourceExtension, OpString, OpLine, OpNoLine,
// OpModuleProcessed), keeping the names (OpName, OpMemberName). The shaders are compiled with
// `glslc -O -g` because -O alone strips every name, and the host identifies the resources of a
// module's descriptor set (set 1) by their names (src/gpu/shader_interface.h); what -g adds
// beyond the names would triple the embedded SPIR-V. The code itself is what -O alone makes.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: spv_strip IN.spv OUT.spv\n");
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "spv_strip: cannot read %s\n", argv[1]);
    return 1;
  }
  const std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
  if (bytes.size() % 4 != 0 || bytes.size() < 20) {
    std::fprintf(stderr, "spv_strip: %s is not SPIR-V\n", argv[1]);
    return 1;
  }
  std::vector<uint32_t> words(bytes.size() / 4);
  std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(words.data()));
  if (words[0] != 0x07230203u) {
    std::fprintf(stderr, "spv_strip: %s is not SPIR-V (or not little-endian)\n", argv[1]);
    return 1;
  }
  std::vector<uint32_t> out(words.begin(), words.begin() + 5);  // the header
  for (size_t i = 5; i < words.size();) {
    const uint32_t count = words[i] >> 16, opcode = words[i] & 0xffffu;
    if (count == 0 || i + count > words.size()) {
      std::fprintf(stderr, "spv_strip: %s: a malformed instruction at word %zu\n", argv[1], i);
      return 1;
    }
    const bool debug = opcode == 2 || opcode == 3 || opcode == 4 ||  // OpSource*
                       opcode == 7 || opcode == 8 ||                 // OpString, OpLine
                       opcode == 317 || opcode == 330;               // OpNoLine, OpModuleProcessed
    if (!debug) out.insert(out.end(), words.begin() + long(i), words.begin() + long(i + count));
    i += count;
  }
  std::ofstream file(argv[2], std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size() * 4));
  if (!file) {
    std::fprintf(stderr, "spv_strip: cannot write %s\n", argv[2]);
    return 1;
  }
  return 0;
}
