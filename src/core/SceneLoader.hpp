#pragma once
/// Reads a scene TOML file into a validated Scene (docs/input.md; every key in docs/input.md).
#include <string>
#include <vector>

#include "core/Scene.hpp"

namespace gpudem {

/// Parses and validates `path`. `overrides` are `dotted.key=value` strings from `--set`
/// (`value` in TOML syntax; arrays of tables addressed as `material.0.density`), applied
/// before validation. Throws InputError naming file, line and key on any problem; touches
/// no file other than `path`.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace gpudem
