#pragma once
// What `brickyard --help` prints: every command and option, and the exit codes.

namespace brickyard::fw::cli {

extern const char* const kUsage;

}  // namespace brickyard::fw::cli
