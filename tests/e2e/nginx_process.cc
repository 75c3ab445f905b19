// Rewriting a deploy/nginx file for loopback, and running nginx on it.
#include "tests/e2e/nginx_process.h"

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <thread>

#include "tests/e2e/child_process.h"

namespace scallop::testing {
namespace {

// Loopback ports nobody listens on, the kernel's picks. Each stays bound
// until Release, so that no two picks are the same port: two listens on one
// port make nginx serve both from the first server block ("conflicting server
// name"), and an HTTP/1.1 client then reads HTTP/2 frames.
class PortReservations {
 public:
  PortReservations() = default;
  PortReservations(const PortReservations&) = delete;
  PortReservations& operator=(const PortReservations&) = delete;
  ~PortReservations() { Release(); }

  int Reserve() {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof(address);
    const bool ok = bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 &&
                    getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0;
    fds_.push_back(fd);
    return ok ? ntohs(address.sin_port) : -1;
  }
  // Unbinds them all, for nginx to listen on.
  void Release() {
    for (const int fd : fds_) close(fd);
    fds_.clear();
  }

 private:
  std::vector<int> fds_;
};

bool Accepts(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<uint16_t>(port));
  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
  close(fd);
  return ok;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string ReplaceAll(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

}  // namespace

std::unique_ptr<NginxProcess> NginxProcess::Start(
    const std::string& config_path,
    const std::map<std::string, std::vector<std::string>>& upstreams) {
  std::unique_ptr<NginxProcess> process(new NginxProcess());
  char directory_template[] = "/tmp/nginx-test-XXXXXX";
  if (mkdtemp(directory_template) == nullptr) return nullptr;
  process->directory_ = directory_template;
  const std::string& directory = process->directory_;

  static const std::regex upstream_open(R"(^\s*upstream\s+(\S+)\s*\{)");
  static const std::regex server_line(R"(^(\s*)server\s+\S+?(\s[^;]*)?;)");
  static const std::regex listen_line(R"(^(\s*)listen\s+(\d+)(\s[^;]*)?;)");
  std::istringstream in(ReadText(config_path));
  std::ostringstream out;
  std::string line, upstream;  // the upstream block we are in, if any
  bool servers_written = false;
  PortReservations ports;
  for (std::smatch match; std::getline(in, line);) {
    if (std::regex_search(line, match, upstream_open)) {
      upstream = match[1];
      servers_written = false;
    } else if (!upstream.empty() && line.find('}') != std::string::npos) {
      upstream.clear();
    } else if (!upstream.empty() && upstreams.contains(upstream) &&
               std::regex_search(line, match, server_line)) {
      if (!servers_written) {
        for (const std::string& address : upstreams.at(upstream)) {
          out << match[1] << "server " << address << match[2] << ";\n";
        }
      }
      servers_written = true;
      continue;
    } else if (std::regex_search(line, match, listen_line)) {
      // Server blocks sharing a configured port share its stand-in too.
      const int configured = std::stoi(match[2]);
      if (!process->addresses_.contains(configured)) {
        process->addresses_[configured] = "127.0.0.1:" + std::to_string(ports.Reserve());
      }
      line = std::string(match[1]) + "listen " + process->addresses_[configured] +
             std::string(match[3]) + ";";
    }
    out << line << '\n';
  }
  process->config_ = ReplaceAll(ReplaceAll(out.str(), "/var/log/nginx/", directory + "/"),
                                "/var/cache/nginx/", directory + "/");
  std::ofstream(directory + "/site.conf") << process->config_;
  // As root, nginx's workers would run as nobody, who may not write here.
  std::ofstream(directory + "/nginx.conf")
      << (geteuid() == 0 ? "user root;\n" : "") << "daemon off;\nworker_processes 1;\n"
      << "pid " << directory << "/nginx.pid;\nerror_log " << directory << "/error.log info;\n"
      << "events { worker_connections 1024; }\nhttp {\n"
      << "  client_body_temp_path " << directory << "/client_body;\n"
      << "  proxy_temp_path " << directory << "/proxy;\n"
      << "  fastcgi_temp_path " << directory << "/fastcgi;\n"
      << "  uwsgi_temp_path " << directory << "/uwsgi;\n"
      << "  scgi_temp_path " << directory << "/scgi;\n"
      << "  include " << directory << "/site.conf;\n}\n";

  const std::string error_log = directory + "/error.log", conf = directory + "/nginx.conf",
                    prefix = directory + "/";
  const std::string console_path = directory + "/console.log";
  const int console = open(console_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ports.Release();
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    // nginx must not hold the test's stdout and stderr: a test that dies
    // without stopping it would leave CTest waiting for their end until its
    // timeout. The master dies with the test (its workers and cache
    // processes do not: nginx has no such option for them).
    dup2(console, STDOUT_FILENO);
    dup2(console, STDERR_FILENO);
    DieWithTheTest(parent);
    execl(NGINX_PATH, NGINX_PATH, "-p", prefix.c_str(), "-e", error_log.c_str(), "-c", conf.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  close(console);
  process->pid_ = pid;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  for (const auto& [configured, address] : process->addresses_) {
    const int port = std::stoi(address.substr(address.rfind(':') + 1));
    while (!Accepts(port)) {
      if (std::chrono::steady_clock::now() > deadline || waitpid(pid, nullptr, WNOHANG) == pid) {
        std::cerr << "nginx did not start; error log:\n"
                  << ReadText(error_log) << ReadText(console_path) << '\n';
        return nullptr;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  return process;
}

NginxProcess::~NginxProcess() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (waitpid(pid_, nullptr, WNOHANG) != pid_) {
      if (std::chrono::steady_clock::now() > deadline) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  if (!directory_.empty()) {
    std::error_code ignored;
    std::filesystem::remove_all(directory_, ignored);
  }
}

std::string NginxProcess::Address(int configured_port) const {
  const auto found = addresses_.find(configured_port);
  return found == addresses_.end() ? "" : found->second;
}

std::string NginxProcess::ReadFile(const std::string& name) const {
  return ReadText(directory_ + "/" + name);
}

}  // namespace scallop::testing
