#pragma once
// The names OEM7 ASCII logs print for the enums of oem7_messages.hpp ("SOL_COMPUTED", "INS_PPP",
// "FINESTEERING"), both ways. A name the tables lack reads as nothing: the ASCII decoder refuses
// the log as malformed rather than invent a number.
#include "oem7_messages.hpp"

#include <optional>
#include <string_view>

namespace brickyard::drivers {

std::optional<TimeStatus> time_status_from_name(std::string_view name);
std::optional<SolutionStatus> solution_status_from_name(std::string_view name);
std::optional<PositionType> position_type_from_name(std::string_view name);
std::optional<InsStatus> ins_status_from_name(std::string_view name);
std::optional<uint32_t> datum_from_name(std::string_view name);

// The ASCII name, or "" for a number the tables lack.
std::string_view name_of(TimeStatus value);
std::string_view name_of(SolutionStatus value);
std::string_view name_of(PositionType value);
std::string_view name_of(InsStatus value);

}  // namespace brickyard::drivers
