// The verifier's reports as the API carries them (VerifyResponse.field and .layered) and back,
// shared by scallopd, which fills them, and the CLI, which prints a server's report as it prints
// its own.
#pragma once

#include <span>
#include <string>

#include "scallop/v1/scallop.pb.h"
#include "scallop/verify/field_verifier.h"
#include "scallop/verify/layer_verifier.h"

namespace scallop {

// Field for field; the verdict as passed().
v1::FieldVerifyResponse FieldVerifyToMessage(const FieldVerifyReport& report);
// The fields the message carries; conflict_ok from conflicts, maximal_ok as given (the message
// holds no outside count: those points are 0 in a world's window).
FieldVerifyReport FieldVerifyFromMessage(const v1::FieldVerifyResponse& message, bool maximal_ok);

// A layered world's report, each layer under its name (names[k] for layer k).
v1::LayeredVerifyResponse LayeredVerifyToMessage(const LayerVerifyReport& report,
                                                 std::span<const std::string> names);
LayerVerifyReport LayeredVerifyFromMessage(const v1::LayeredVerifyResponse& message);

}  // namespace scallop
