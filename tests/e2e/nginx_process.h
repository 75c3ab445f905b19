// A real nginx for end-to-end tests, running a configuration of deploy/nginx/
// as tested: the file is copied into a temporary directory with only the
// addresses and paths changed (the replicas' addresses for the upstreams'
// servers, free loopback ports for the listens, the directory for logs and
// caches), included from a generated top-level nginx.conf with its own pid,
// error log and temp paths, and run in the foreground (daemon off).
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace scallop::testing {

class NginxProcess {
 public:
  // Starts NGINX_PATH on `config_path` (an http-level file). In each
  // `upstream NAME { ... }` block named in `upstreams`, the `server` lines are
  // replaced by one line per address, with the first line's parameters
  // (max_fails=...). Each PORT of a `listen PORT ...;` gets a free loopback
  // port of its own (the same one for every block listening on PORT); every
  // "/var/log/nginx/" and "/var/cache/nginx/" becomes the directory. Waits
  // until every listen port accepts. Null (with nginx's error log on stderr)
  // when it fails. nginx writes its stdout and stderr to the directory, and
  // is killed when the thread that started it ends: start it from the test's
  // main thread.
  static std::unique_ptr<NginxProcess> Start(
      const std::string& config_path,
      const std::map<std::string, std::vector<std::string>>& upstreams);
  ~NginxProcess();  // stops nginx (SIGTERM, then SIGKILL) and removes the directory

  // "127.0.0.1:PORT" now listening for what the file's `listen PORT` said.
  std::string Address(int configured_port) const;
  // The configuration nginx runs, as rewritten.
  const std::string& Config() const { return config_; }
  // The text of a file nginx wrote in its directory (e.g. its access log).
  std::string ReadFile(const std::string& name) const;

 private:
  NginxProcess() = default;

  int pid_ = -1;
  std::string directory_;
  std::string config_;
  std::map<int, std::string> addresses_;
};

}  // namespace scallop::testing
