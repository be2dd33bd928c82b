#pragma once
// What makes a DBC's message or signal unusable on the car (dbc_reader.cpp reports each as an
// error at its line): a length the payload cannot hold, a zero factor, a range the signal's bits
// cannot carry, two signals on the same bit, a multiplexed signal without its multiplexer.
#include "dbc.hpp"

#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

// "" when the signal is usable in `message`, else what is wrong ("length 0", ...).
std::string signal_problem(const DbcSignal& signal, const DbcMessage& message);

// A SIG_VALTYPE_ float needs 32 bits, a double 64: "" or what is wrong.
std::string value_type_problem(const DbcSignal& signal);

struct LayoutProblem {
  int line = 0;
  std::string what;
};
// Signals sharing a bit where both can be present (the same multiplexer value, or either not
// multiplexed), and multiplexed signals in a message with no multiplexer. Messages with extended
// multiplexing and Vector's independent-signal holder are not checked (pack and unpack refuse them).
std::vector<LayoutProblem> message_layout_problems(const DbcMessage& message);

}  // namespace brickyard::vehicle_interface
