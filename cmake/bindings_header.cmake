# gpu::Binding from the GLSL declarations (shaders/common/bindings_inc.glsl), so the binding
# numbers are written once. A declaration's name gives the enumerator: an image or sampler
# `sky_view_lut` -> kSkyViewLut, a block `StarsBlock { ... }` -> kStars. The numbers must run
# 0..n-1 without a gap or a repeat. Written only when it changes (nothing rebuilds otherwise).
function(nephele_bindings_header glsl out)
  file(READ ${glsl} text)
  string(REGEX MATCHALL "layout\\([^)]*binding = [0-9]+[^)]*\\)[^;]*" declarations "${text}")
  set(count 0)
  set(enumerators "")
  set(names "")
  foreach(declaration IN LISTS declarations)
    string(REGEX MATCH "binding = ([0-9]+)" _ "${declaration}")
    set(number ${CMAKE_MATCH_1})
    if(NOT number EQUAL count)
      message(FATAL_ERROR "${glsl}: binding ${number} follows ${count} bindings; they must run 0, 1, 2, ...")
    endif()
    if(declaration MATCHES "([A-Za-z0-9]+)Block[ \t\n]*{")
      set(camel ${CMAKE_MATCH_1})
      set(glsl_name "${CMAKE_MATCH_1}Block")
    elseif(declaration MATCHES "([a-z0-9_]+)[ \t\n]*$")
      set(glsl_name ${CMAKE_MATCH_1})
      string(REPLACE "_" ";" words ${glsl_name})
      set(camel "")
      foreach(word IN LISTS words)
        string(SUBSTRING ${word} 0 1 first)
        string(SUBSTRING ${word} 1 -1 rest)
        string(TOUPPER ${first} first)
        string(APPEND camel "${first}${rest}")
      endforeach()
    else()
      message(FATAL_ERROR "${glsl}: no name in the declaration of binding ${number}")
    endif()
    string(APPEND enumerators "  k${camel} = ${number},\n")
    string(APPEND names "      \"${glsl_name}\",\n")
    math(EXPR count "${count} + 1")
  endforeach()
  set(header "// Generated from shaders/common/bindings_inc.glsl by cmake/bindings_header.cmake; do not edit.
#pragma once

#include <cstdint>

namespace nephele::gpu {

// The bindings of set 0, numbered as bindings_inc.glsl declares them.
enum Binding : uint32_t {
${enumerators}  kBindingCount = ${count}
};

// The GLSL name of a binding (its block's name for a buffer), for messages.
inline const char* binding_name(Binding binding) {
  static const char* const names[] = {
${names}  };
  return binding < kBindingCount ? names[binding] : \"(no such binding)\";
}

}  // namespace nephele::gpu
")
  set(old "")
  if(EXISTS ${out})
    file(READ ${out} old)
  endif()
  if(NOT old STREQUAL header)
    file(WRITE ${out} "${header}")
  endif()
endfunction()
