// Starting, signalling and reaping scallopd with fork and exec.
#include "tests/e2e/scallopd_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "tests/e2e/child_process.h"

namespace scallop::testing {
namespace {

// One line of `fd`, without its newline; empty after `timeout` or at its end.
std::string ReadLine(int fd, std::chrono::milliseconds timeout) {
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd ready{fd, POLLIN, 0};
    if (poll(&ready, 1, 100) <= 0) continue;
    char c;
    if (read(fd, &c, 1) != 1) break;
    if (c == '\n') return line;
    line.push_back(c);
  }
  return "";
}

// The first line the server prints on stdout: "scallopd listening on HOST:PORT".
std::string ReadAddressLine(int fd, std::chrono::milliseconds timeout) {
  const std::string line = ReadLine(fd, timeout);
  const std::string prefix = "scallopd listening on ";
  return line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : "";
}

}  // namespace

std::unique_ptr<ScallopdProcess> ScallopdProcess::Start(
    const std::vector<std::string>& arguments, const std::string& listen,
    const client::ConnectionOptions& connection) {
  std::unique_ptr<ScallopdProcess> process(new ScallopdProcess());
  process->connection_ = connection;
  char log_template[] = "/tmp/scallopd-test-XXXXXX";
  const int log_fd = mkstemp(log_template);
  process->log_path_ = log_template;
  int out[2];
  if (log_fd < 0 || pipe(out) != 0) return nullptr;
  const char* under_test = std::getenv("SCALLOPD_UNDER_TEST");
  std::vector<std::string> argv_strings{under_test != nullptr ? under_test : SCALLOPD_PATH,
                                        "--listen", listen};
  argv_strings.insert(argv_strings.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& s : argv_strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out[1], STDOUT_FILENO);
    dup2(log_fd, STDERR_FILENO);
    close(out[0]);
    DieWithTheTest(parent);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(out[1]);
  close(log_fd);
  process->pid_ = pid;
  process->stdout_fd_ = out[0];
  process->address_ = ReadAddressLine(out[0], std::chrono::seconds(20));
  if (process->address_.empty()) {
    std::cerr << "scallopd did not start; log:\n" << process->Log() << '\n';
    return nullptr;
  }
  client::ScallopClient client = process->Client();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    bool serving = false;
    client.CheckHealth(serving, {.timeout = std::chrono::milliseconds(500)});
    if (serving) return process;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::cerr << "scallopd never became SERVING; log:\n" << process->Log() << '\n';
  return nullptr;
}

ScallopdProcess::~ScallopdProcess() {
  if (pid_ > 0 && !exited_) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (stdout_fd_ >= 0) close(stdout_fd_);
  if (!log_path_.empty()) unlink(log_path_.c_str());
}

std::string ScallopdProcess::ReadStdoutLine(std::chrono::milliseconds timeout) const {
  return ReadLine(stdout_fd_, timeout);
}

std::string ScallopdProcess::ReadAnnouncedAddress(const std::string& prefix) const {
  for (int line = 0; line < 3; ++line) {  // the metrics and HTTP lines, in either order
    const std::string text = ReadStdoutLine(std::chrono::seconds(10));
    if (text.starts_with(prefix)) return text.substr(text.rfind(' ') + 1);
  }
  return "";
}

void ScallopdProcess::Signal(int signal_number) const { kill(pid_, signal_number); }

int ScallopdProcess::WaitForExit(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      exited_ = true;
      return WIFEXITED(status) ? WEXITSTATUS(status) : -2 - WTERMSIG(status);
    }
    if (std::chrono::steady_clock::now() >= deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

std::string ScallopdProcess::Log() const {
  std::ifstream in(log_path_);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string ScallopdProcess::WaitForLog(const std::string& text,
                                        std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string log = Log();
  while (log.find(text) == std::string::npos && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    log = Log();
  }
  return log;
}

}  // namespace scallop::testing
