// nephele — the library's version (the CLI's --version, the EXR header's software).
#pragma once

namespace nephele {
inline constexpr const char* kVersion = "0.1.0";  // as project() in CMakeLists.txt
}  // namespace nephele
