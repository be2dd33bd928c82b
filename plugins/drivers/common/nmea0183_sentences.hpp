#pragma once
// The fields of one NMEA 0183 sentence read into nmea0183_messages.hpp's structs. Framing and the
// checksum are nmea0183.hpp's; this reads the text between '$' and '*' and says why it could not.
#include "nmea0183_messages.hpp"

#include <string_view>

namespace brickyard::drivers {

enum class SentenceReadResult { ok, unknown_sentence, malformed };

// `text`: the sentence between its '$' and its '*' ("GPGGA,220147.50,...").
SentenceReadResult read_sentence(std::string_view text, NmeaMessage& out);

}  // namespace brickyard::drivers
