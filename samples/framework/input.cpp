// SPDX-License-Identifier: MIT
#include "input.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace prt::sample {
namespace {

MouseButton parse_button(const std::string& word, const std::string& where) {
  if (word == "left") return MouseButton::Left;
  if (word == "right") return MouseButton::Right;
  throw std::runtime_error(where + ": expected left or right, got '" + word + "'");
}

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

}  // namespace

std::vector<InputEvent> read_input_script(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot read the input script");
  std::vector<InputEvent> events;
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream in(line);
    InputEvent event;
    std::string verb;
    if (!(in >> event.frame)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      throw std::runtime_error(path + ":" + std::to_string(number) + ": expected a frame number");
    }
    const std::string where = path + ":" + std::to_string(number);
    if (!(in >> verb)) throw std::runtime_error(where + ": expected an event after the frame");
    bool ok = true;
    std::string word;
    if (verb == "move") {
      event.kind = InputEvent::Kind::Move;
      ok = static_cast<bool>(in >> event.x >> event.y);
    } else if (verb == "press" || verb == "release") {
      event.kind = verb == "press" ? InputEvent::Kind::Press : InputEvent::Kind::Release;
      ok = static_cast<bool>(in >> word);
      if (ok) event.button = parse_button(word, where);
    } else if (verb == "scroll") {
      event.kind = InputEvent::Kind::Scroll;
      ok = static_cast<bool>(in >> event.x);
    } else if (verb == "key") {
      event.kind = InputEvent::Kind::Key;
      ok = static_cast<bool>(in >> word);
      event.key = upper(word);
    } else if (verb == "drop") {
      event.kind = InputEvent::Kind::Drop;
      while (in >> word) event.paths.push_back(word);
      ok = !event.paths.empty();
    } else if (verb == "resize") {
      event.kind = InputEvent::Kind::Resize;
      ok = static_cast<bool>(in >> event.x >> event.y) && event.x >= 1 && event.y >= 1 &&
           event.x <= 16384 && event.y <= 16384;
    } else {
      throw std::runtime_error(where + ": unknown event '" + verb + "'");
    }
    if (!ok) throw std::runtime_error(where + ": incomplete '" + verb + "' event");
    events.push_back(event);
  }
  return events;
}

void replay(const std::vector<InputEvent>& events, long frame, InputSink& sink) {
  for (const InputEvent& event : events) {
    if (event.frame != frame) continue;
    switch (event.kind) {
      case InputEvent::Kind::Move:
        sink.cursor(event.x, event.y);
        break;
      case InputEvent::Kind::Press:
      case InputEvent::Kind::Release:
        sink.button(event.button, event.kind == InputEvent::Kind::Press);
        break;
      case InputEvent::Kind::Scroll:
        sink.scroll(event.x);
        break;
      case InputEvent::Kind::Key:
        sink.key(event.key);
        break;
      case InputEvent::Kind::Drop:
        sink.drop(event.paths);
        break;
      case InputEvent::Kind::Resize:
        sink.resize(int(event.x), int(event.y));
        break;
    }
  }
}

}  // namespace prt::sample
