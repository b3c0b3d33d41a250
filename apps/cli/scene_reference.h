// nephele CLI — the scene reference (docs/scene-reference.md), generated from the table of
// scene fields: every key with its unit, allowed values, default, flag and meaning.
#pragma once

#include <string>

namespace nephele::cli {

// The whole page as Markdown; `nephele keys` prints it.
std::string scene_reference_markdown();

}  // namespace nephele::cli
