// A real scallopd child process for end-to-end tests: started on a free
// loopback port (it binds port 0 and prints the address it got), ready once
// its standard health check says SERVING, killed if a test leaves it running.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "scallop_client.h"

namespace scallop::testing {

class ScallopdProcess {
 public:
  // Starts SCALLOPD_PATH (or $SCALLOPD_UNDER_TEST, to run the tests against
  // another build, e.g. to see a new test fail on the old server) with
  // `arguments` plus --listen `listen`, and waits up to 20 s for SERVING,
  // asked over `connection` (TLS for a TLS server). Client() connects with it.
  // Null (with the reason on stderr) if it fails. The server is killed when
  // the thread that started it ends (PR_SET_PDEATHSIG), so that a test that
  // dies leaves none behind: start it from the test's main thread.
  static std::unique_ptr<ScallopdProcess> Start(const std::vector<std::string>& arguments,
                                                const std::string& listen = "127.0.0.1:0",
                                                const client::ConnectionOptions& connection = {});
  ~ScallopdProcess();

  const std::string& address() const { return address_; }
  client::ScallopClient Client() const {
    return client::ScallopClient::Connect(address_, connection_);
  }
  client::ScallopClient Client(const client::ConnectionOptions& connection) const {
    return client::ScallopClient::Connect(address_, connection);
  }

  // The next line scallopd printed on stdout after the address line (e.g.
  // "scallopd metrics on HOST:PORT"), or empty after `timeout`.
  std::string ReadStdoutLine(std::chrono::milliseconds timeout) const;
  // The HOST:PORT at the end of the first of the next few stdout lines that
  // starts with `prefix` ("scallopd http on "), or empty if none does.
  std::string ReadAnnouncedAddress(const std::string& prefix) const;

  void Signal(int signal_number) const;
  // The exit code once the process has exited, or -1 after `timeout`
  // (-2 - signal when it died of a signal).
  int WaitForExit(std::chrono::milliseconds timeout);
  // Everything it wrote to stderr (its log) so far.
  std::string Log() const;
  // The log once it holds `text` (a call's line is written when the call
  // ends), or as it is after `timeout`.
  std::string WaitForLog(const std::string& text, std::chrono::milliseconds timeout) const;

 private:
  ScallopdProcess() = default;

  int pid_ = -1;
  int stdout_fd_ = -1;
  std::string log_path_;
  std::string address_;
  client::ConnectionOptions connection_;
  bool exited_ = false;
};

}  // namespace scallop::testing
