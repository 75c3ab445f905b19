// The parts of `scallop analyze` for worlds that are judged apart from the plain series: a
// radius field's (per band of R) and a layered world's (per layer and the union). Each prints
// its report and returns the exit code (analyze_command.cc dispatches to them).
#pragma once

#include "client/analysis/series.h"
#include "scallop/field/radius_field.h"

namespace scallop::cli {

// A radius field's sets (the field sampler or the field Bridson on --domain, a world on --rect,
// or --input files), judged against the field.
int RunFieldAnalyze(const AnalyzeArguments& arguments, const RadiusFieldSpec& spec);

// A layered world's sets, on one --rect window of the plane or sampled on a --domain alone.
int RunLayeredAnalyze(const AnalyzeArguments& arguments);

}  // namespace scallop::cli
