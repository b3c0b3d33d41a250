// Files embedded into the binary at build time (cmake/embed_files.cmake).
#pragma once
#include <cstddef>
#include <string_view>

struct EmbeddedFile {
  const char* name;
  const unsigned char* data;
  size_t size;
};

// Looks up `name` in `files`; returns nullptr when absent.
inline const EmbeddedFile* find_embedded(const EmbeddedFile* files, size_t count,
                                         std::string_view name) {
  for (size_t i = 0; i < count; ++i)
    if (name == files[i].name) return &files[i];
  return nullptr;
}
