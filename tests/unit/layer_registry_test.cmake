# Translucent layers register themselves from their folders (cmake/module_registry.cmake):
# a folder holding NAME_layer.glsl is included and blended, in the folders' order; a folder
# without one adds nothing. Run by ctest: cmake -DREGISTRY=... -DWORK=... -P this file.
file(REMOVE_RECURSE ${WORK})
file(WRITE ${WORK}/render/modules/beta/beta_layer.glsl "// beta\n")
file(WRITE ${WORK}/render/modules/alpha/alpha_layer.glsl "// alpha\n")
file(WRITE ${WORK}/render/modules/gamma/gamma_medium.glsl "// a medium, not a layer\n")
include(${REGISTRY})
nephele_layer_registry(${WORK}/render/modules ${WORK}/layer_list_inc.glsl)
file(READ ${WORK}/layer_list_inc.glsl text)
foreach(expected
    "#include \"render/modules/alpha/alpha_layer.glsl\"\n#include \"render/modules/beta/beta_layer.glsl\"\n"
    "  layer = alpha_layer(uv, distance_m);\n  blend_layer(layer, distance_m, b);\n  layer = beta_layer(uv, distance_m);\n"
    "  t *= 1.0f - alpha_layer(uv, distance_m).a;\n  t *= 1.0f - beta_layer(uv, distance_m).a;\n")
  string(FIND "${text}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "layer_list_inc.glsl lacks:\n${expected}\nIt reads:\n${text}")
  endif()
endforeach()
string(FIND "${text}" "gamma" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "a folder without a *_layer.glsl was listed:\n${text}")
endif()
