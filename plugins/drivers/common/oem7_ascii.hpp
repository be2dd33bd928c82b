#pragma once
// OEM7 ASCII logs ("#BESTPOSA,COM1,...;SOL_COMPUTED,...*046a3e09") read into the structs of
// oem7_messages.hpp. Framing and the CRC check are novatel_oem7.hpp's; this reads the text between
// the sync character and the '*', field by field, and says why it could not.
#include "oem7_messages.hpp"

#include <string_view>

namespace brickyard::drivers {

enum class AsciiReadResult { ok, unknown_message, malformed };

// `text`: the log between its '#' ('%' with `short_header`) and its '*'.
AsciiReadResult read_ascii_log(std::string_view text, bool short_header, Oem7Message& out);

}  // namespace brickyard::drivers
