// SPDX-License-Identifier: MIT
#include "reference_run.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

extern char** environ;

namespace prt::shadowfield_app {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string read_tail(const std::string& path, std::size_t bytes) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const std::streamoff size = in.tellg();
  const std::streamoff from = size > std::streamoff(bytes) ? size - std::streamoff(bytes) : 0;
  in.seekg(from);
  std::string text(std::size_t(size - from), '\0');
  in.read(text.data(), std::streamsize(text.size()));
  return text;
}

}  // namespace

std::string last_line_of(const std::string& path) {
  const std::string text = read_tail(path, 4096);
  std::string line, last;
  std::istringstream lines(text);
  // Progress bars rewrite their line with '\r': the part after the last one is the latest.
  while (std::getline(lines, line)) {
    const std::size_t cr = line.find_last_of('\r', line.size() > 1 ? line.size() - 2 : 0);
    if (cr != std::string::npos && cr + 1 < line.size()) line = line.substr(cr + 1);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) last = line;
  }
  return last;
}

void ReferenceRun::start(const std::string& tool, const std::vector<std::string>& arguments,
                         const std::string& log) {
  cancel();
  log_ = log;
  why_.clear();
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(tool.c_str()));
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  // A group of its own, so that cancelling ends whatever the tool started too.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int failed = posix_spawnp(&pid_, tool.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  started_ = ended_ = now_seconds();
  if (failed != 0) {
    pid_ = -1;
    state_ = State::Failed;
    why_ = "cannot run " + tool + ": " + std::strerror(failed);
    return;
  }
  state_ = State::Running;
}

void ReferenceRun::cancel() {
  if (pid_ > 0) {
    kill(-pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  pid_ = -1;
  state_ = State::Idle;
}

ReferenceRun::State ReferenceRun::poll() {
  if (state_ != State::Running) return state_;
  int status = 0;
  const pid_t ended = waitpid(pid_, &status, WNOHANG);
  if (ended == 0) return state_;
  pid_ = -1;
  ended_ = now_seconds();
  if (ended > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    state_ = State::Done;
    return state_;
  }
  state_ = State::Failed;
  const std::string exit = ended > 0 && WIFEXITED(status)
                               ? "exit status " + std::to_string(WEXITSTATUS(status))
                               : "ended abnormally";
  why_ = "reference: " + exit + ": " + last_line_of(log_);
  return state_;
}

double ReferenceRun::progress() const {
  if (state_ == State::Done) return 1.0;
  const std::string text = read_tail(log_, 512);
  const std::size_t percent = text.rfind('%');
  if (percent == std::string::npos || percent == 0) return -1.0;
  std::size_t begin = percent;
  while (begin > 0 &&
         (std::isdigit(static_cast<unsigned char>(text[begin - 1])) || text[begin - 1] == '.'))
    --begin;
  if (begin == percent) return -1.0;
  return std::atof(text.substr(begin, percent - begin).c_str()) / 100.0;
}

double ReferenceRun::seconds() const {
  return (state_ == State::Running ? now_seconds() : ended_) - started_;
}

}  // namespace prt::shadowfield_app
