// --format and --seams registration.
#include "client/options/format_options.h"

#include <CLI/CLI.hpp>
#include <map>
#include <string>

namespace scallop::cli {

void AddFormatOption(CLI::App& command, PointFormat& format) {
  const std::map<std::string, PointFormat> formats(PointFormatNames().begin(),
                                                   PointFormatNames().end());
  command.add_option("--format", format, "csv, json, svg or none")
      ->transform(CLI::CheckedTransformer(formats, CLI::ignore_case))
      ->option_text("csv|json|svg|none (default csv)");
}

void AddFormatAndSeamsOptions(CLI::App& command, PointFormat& format, bool& seams) {
  AddFormatOption(command, format);
  command.add_flag("--seams", seams, "svg: draw the region seams (every 16 d)");
}

}  // namespace scallop::cli
