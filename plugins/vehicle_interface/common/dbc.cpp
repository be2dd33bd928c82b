#include "dbc.hpp"

namespace brickyard::vehicle_interface {

// Linear lookups: a car's DBC has tens of messages of a few signals each, and a frame is matched
// to its message in fewer comparisons than a hash of its id would take.
const DbcSignal* DbcMessage::find_signal(std::string_view signal_name) const {
  for (const DbcSignal& s : signals)
    if (s.name == signal_name) return &s;
  return nullptr;
}

const DbcMessage* DbcDatabase::find(uint32_t id, bool extended) const {
  for (const DbcMessage& m : messages)
    if (m.id == id && m.extended == extended && !m.independent_signals) return &m;
  return nullptr;
}

const DbcMessage* DbcDatabase::find(std::string_view message_name) const {
  for (const DbcMessage& m : messages)
    if (m.name == message_name) return &m;
  return nullptr;
}

size_t DbcDatabase::signal_count() const {
  size_t n = 0;
  for (const DbcMessage& m : messages) n += m.signals.size();
  return n;
}

}  // namespace brickyard::vehicle_interface
