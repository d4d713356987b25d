// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/detail/json_reader.h"
#include "meshmorph/app/case_file.h"

namespace meshmorph::detail {

/// A level-set object `{"<kind>": value}` (exactly one key); relative files against `base`.
LevelSet parse_level_set(const nlohmann::json& j, const JsonWhere& w, const std::filesystem::path& base);

/// One entry of "boundary": "group" plus exactly one motion key.
BoundaryCondition parse_boundary_condition(const nlohmann::json& j, const JsonWhere& w,
                                           const std::filesystem::path& base);

/// Compiles a muparser expression in x, y, z with constant pi; throws InputError at `w`
/// with muparser's message and the character position.
void check_expression(const std::string& expression, const JsonWhere& w);

/// `relative` resolved against `base` (unless absolute); throws at `w` if it is not a file.
std::filesystem::path existing_file(const std::string& relative, const std::filesystem::path& base,
                                    const JsonWhere& w);

}  // namespace meshmorph::detail
