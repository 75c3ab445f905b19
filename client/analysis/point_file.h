// Reads the point files the CLI writes, for `scallop analyze --input`: the CSV
// (`x,y`, `id,x,y`, and a field world's `x,y,r` and `id,x,y,r`, with a header) and JSON (`{"x":
// [...], "y": [...]}`) of `scallop generate`, `scallop plane` and `scallop points`.
#pragma once

#include <string>
#include <vector>

#include "scallop/base/status.h"
#include "scallop/geometry/vec2.h"

namespace scallop::cli {

// The points of the file at `path`, in file order. JSON when the first
// non-blank character is '{', CSV otherwise. O(file size).
// Rejects (INVALID_ARGUMENT, naming the path and, for CSV, the line): an
// unreadable file, a CSV header other than those four, a row with the
// wrong number of fields or a field that is not a finite number, JSON without
// equally long numeric arrays "x" and "y", and a file with no point.
StatusOr<std::vector<Vec2>> ReadPointFile(const std::string& path);

}  // namespace scallop::cli
