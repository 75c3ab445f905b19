// The --format (and --seams) options every command that prints points takes,
// registered in one place so they read and behave the same everywhere.
#pragma once

#include "client/options/cli_fwd.h"
#include "client/output/point_output.h"

namespace scallop::cli {

// Adds --format csv|json|svg|none (case-insensitive, default csv) storing
// into `format`, which must outlive parsing.
void AddFormatOption(CLI::App& command, PointFormat& format);

// Adds --format as above and --seams (SVG: dashed region seams every 16 d).
void AddFormatAndSeamsOptions(CLI::App& command, PointFormat& format, bool& seams);

}  // namespace scallop::cli
