// SPDX-License-Identifier: MIT
// The reference for the current placement, rendered in the background by a child process
// (`prt-bake shadowfield-reference`): started with its arguments, polled each frame for its end
// and for the progress it prints, cancelled (killed) when what it renders has changed.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace prt::shadowfield_app {

class ReferenceRun {
 public:
  enum class State { Idle, Running, Done, Failed };

  ReferenceRun() = default;
  ReferenceRun(const ReferenceRun&) = delete;
  ReferenceRun& operator=(const ReferenceRun&) = delete;
  ~ReferenceRun() { cancel(); }

  // Runs `tool` with `arguments`, its stdout and stderr into `log`; cancels a run in progress.
  // Failed (with why()) when it cannot be started.
  void start(const std::string& tool, const std::vector<std::string>& arguments,
             const std::string& log);
  // Kills a running child and waits for it; back to Idle.
  void cancel();
  // Checks whether the child has ended; returns the state.
  State poll();
  State state() const { return state_; }
  // The last percentage the tool printed (0..1), or a negative number before any.
  double progress() const;
  double seconds() const;
  // Why it failed: the exit status and the log's last line.
  const std::string& why() const { return why_; }

 private:
  pid_t pid_ = -1;
  State state_ = State::Idle;
  std::string log_, why_;
  double started_ = 0.0, ended_ = 0.0;
};

// The log's last line that is not empty.
std::string last_line_of(const std::string& path);

}  // namespace prt::shadowfield_app
