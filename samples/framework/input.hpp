// SPDX-License-Identifier: MIT
// Input as the framework sees it: a few events, one set of handlers (InputSink) that the GLFW
// callbacks call in a window, and an input script that replays timed events into the same
// handlers, windowed or headless. The script is how tests drive a sample: its events land on
// exact frames, so a run is reproducible, which events from a window system are not.
//
// Script lines (blank lines and text after '#' are ignored), FRAME the frame (from 0) before
// whose drawing the event is handled, X Y window pixels from the top left:
//   FRAME move X Y            the cursor moves to (X, Y)
//   FRAME press left|right    a mouse button goes down at the cursor
//   FRAME release left|right
//   FRAME scroll STEPS        the wheel (positive: away from the user)
//   FRAME key NAME            a key is pressed and released (a letter, a digit, F1..F12,
//                             escape, space)
//   FRAME drop PATH...        files dropped on the window (paths without spaces)
//   FRAME resize W H          the window (or the headless frame) is resized to W x H pixels, as
//                             a user dragging its border would
#pragma once

#include <string>
#include <vector>

namespace prt::sample {

enum class MouseButton { Left, Right };

// Keys by name: letters and digits as upper-case characters, "F12", "ESCAPE", "SPACE".
struct InputSink {
  virtual ~InputSink() = default;
  virtual void cursor(double x, double y) = 0;
  virtual void button(MouseButton button, bool pressed) = 0;
  virtual void scroll(double steps) = 0;
  virtual void key(const std::string& name) = 0;
  virtual void drop(const std::vector<std::string>& paths) = 0;
  virtual void resize(int width, int height) = 0;
};

struct InputEvent {
  enum class Kind { Move, Press, Release, Scroll, Key, Drop, Resize } kind = Kind::Move;
  long frame = 0;
  double x = 0.0, y = 0.0;  // Move: the cursor; Scroll: steps in x; Resize: the size
  MouseButton button = MouseButton::Left;
  std::string key;
  std::vector<std::string> paths;
};

// Reads a script; throws std::runtime_error naming the file and line on a bad line.
std::vector<InputEvent> read_input_script(const std::string& path);

// Feeds every event of `frame` to `sink`, in file order.
void replay(const std::vector<InputEvent>& events, long frame, InputSink& sink);

}  // namespace prt::sample
