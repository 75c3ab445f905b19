// The failure lines and exit codes of command_exit.h.
#include "client/commands/command_exit.h"

#include <iostream>

#include "scallop_client.h"

namespace scallop::cli {

int ReportBadArguments(std::string_view command, const Status& status) {
  std::cerr << "scallop " << command << ": " << status.message() << '\n';
  return 2;
}

int ReportCallFailure(std::string_view command, const grpc::Status& status) {
  std::cerr << "scallop " << command << ": " << client::DescribeStatus(status) << '\n';
  return 1;
}

}  // namespace scallop::cli
