#include "oem7_enum_names.hpp"

#include <array>
#include <utility>

namespace brickyard::drivers {

namespace {

template <typename Enum>
using NameTable = std::pair<Enum, std::string_view>;

constexpr std::array<NameTable<TimeStatus>, 11> kTimeStatusNames{{
    {TimeStatus::unknown, "UNKNOWN"}, {TimeStatus::approximate, "APPROXIMATE"},
    {TimeStatus::coarse_adjusting, "COARSEADJUSTING"}, {TimeStatus::coarse, "COARSE"},
    {TimeStatus::coarse_steering, "COARSESTEERING"}, {TimeStatus::freewheeling, "FREEWHEELING"},
    {TimeStatus::fine_adjusting, "FINEADJUSTING"}, {TimeStatus::fine, "FINE"},
    {TimeStatus::fine_backup_steering, "FINEBACKUPSTEERING"}, {TimeStatus::fine_steering, "FINESTEERING"},
    {TimeStatus::sattime, "SATTIME"},
}};

constexpr std::array<NameTable<SolutionStatus>, 16> kSolutionStatusNames{{
    {SolutionStatus::computed, "SOL_COMPUTED"}, {SolutionStatus::insufficient_obs, "INSUFFICIENT_OBS"},
    {SolutionStatus::no_convergence, "NO_CONVERGENCE"}, {SolutionStatus::singularity, "SINGULARITY"},
    {SolutionStatus::cov_trace, "COV_TRACE"}, {SolutionStatus::test_dist, "TEST_DIST"},
    {SolutionStatus::cold_start, "COLD_START"}, {SolutionStatus::v_h_limit, "V_H_LIMIT"},
    {SolutionStatus::variance, "VARIANCE"}, {SolutionStatus::residuals, "RESIDUALS"},
    {SolutionStatus::delta_pos, "DELTA_POS"}, {SolutionStatus::negative_var, "NEGATIVE_VAR"},
    {SolutionStatus::integrity_warning, "INTEGRITY_WARNING"}, {SolutionStatus::pending, "PENDING"},
    {SolutionStatus::invalid_fix, "INVALID_FIX"}, {SolutionStatus::unauthorized, "UNAUTHORIZED"},
}};

constexpr std::array<NameTable<PositionType>, 31> kPositionTypeNames{{
    {PositionType::none, "NONE"}, {PositionType::fixedpos, "FIXEDPOS"},
    {PositionType::fixedheight, "FIXEDHEIGHT"}, {PositionType::doppler_velocity, "DOPPLER_VELOCITY"},
    {PositionType::single, "SINGLE"}, {PositionType::psrdiff, "PSRDIFF"}, {PositionType::waas, "WAAS"},
    {PositionType::propagated, "PROPAGATED"}, {PositionType::l1_float, "L1_FLOAT"},
    {PositionType::ionofree_float, "IONOFREE_FLOAT"}, {PositionType::narrow_float, "NARROW_FLOAT"},
    {PositionType::l1_int, "L1_INT"}, {PositionType::wide_int, "WIDE_INT"},
    {PositionType::narrow_int, "NARROW_INT"}, {PositionType::rtk_direct_ins, "RTK_DIRECT_INS"},
    {PositionType::ins_sbas, "INS_SBAS"}, {PositionType::ins_psrsp, "INS_PSRSP"},
    {PositionType::ins_psrdiff, "INS_PSRDIFF"}, {PositionType::ins_rtkfloat, "INS_RTKFLOAT"},
    {PositionType::ins_rtkfixed, "INS_RTKFIXED"}, {PositionType::ppp_converging, "PPP_CONVERGING"},
    {PositionType::ppp, "PPP"}, {PositionType::operational, "OPERATIONAL"}, {PositionType::warning, "WARNING"},
    {PositionType::out_of_bounds, "OUT_OF_BOUNDS"}, {PositionType::ins_ppp_converging, "INS_PPP_CONVERGING"},
    {PositionType::ins_ppp, "INS_PPP"}, {PositionType::ppp_basic_converging, "PPP_BASIC_CONVERGING"},
    {PositionType::ppp_basic, "PPP_BASIC"}, {PositionType::ins_ppp_basic_converging, "INS_PPP_BASIC_CONVERGING"},
    {PositionType::ins_ppp_basic, "INS_PPP_BASIC"},
}};

constexpr std::array<NameTable<InsStatus>, 11> kInsStatusNames{{
    {InsStatus::inactive, "INS_INACTIVE"}, {InsStatus::aligning, "INS_ALIGNING"},
    {InsStatus::high_variance, "INS_HIGH_VARIANCE"}, {InsStatus::solution_good, "INS_SOLUTION_GOOD"},
    {InsStatus::solution_free, "INS_SOLUTION_FREE"}, {InsStatus::alignment_complete, "INS_ALIGNMENT_COMPLETE"},
    {InsStatus::determining_orientation, "DETERMINING_ORIENTATION"},
    {InsStatus::waiting_initial_pos, "WAITING_INITIALPOS"}, {InsStatus::waiting_azimuth, "WAITING_AZIMUTH"},
    {InsStatus::initializing_biases, "INITIALIZING_BIASES"}, {InsStatus::motion_detect, "MOTION_DETECT"},
}};

template <typename Enum, size_t N>
std::optional<Enum> find_value(const std::array<NameTable<Enum>, N>& table, std::string_view name) {
  for (const auto& [value, text] : table)
    if (text == name) return value;
  return std::nullopt;
}

template <typename Enum, size_t N>
std::string_view find_name(const std::array<NameTable<Enum>, N>& table, Enum value) {
  for (const auto& [v, text] : table)
    if (v == value) return text;
  return {};
}

}  // namespace

std::optional<TimeStatus> time_status_from_name(std::string_view n) { return find_value(kTimeStatusNames, n); }
std::optional<SolutionStatus> solution_status_from_name(std::string_view n) { return find_value(kSolutionStatusNames, n); }
std::optional<PositionType> position_type_from_name(std::string_view n) { return find_value(kPositionTypeNames, n); }
std::optional<InsStatus> ins_status_from_name(std::string_view n) { return find_value(kInsStatusNames, n); }

std::optional<uint32_t> datum_from_name(std::string_view name) {
  if (name == "WGS84") return kDatumWgs84;
  if (name == "USER") return kDatumUser;
  return std::nullopt;
}

std::string_view name_of(TimeStatus value) { return find_name(kTimeStatusNames, value); }
std::string_view name_of(SolutionStatus value) { return find_name(kSolutionStatusNames, value); }
std::string_view name_of(PositionType value) { return find_name(kPositionTypeNames, value); }
std::string_view name_of(InsStatus value) { return find_name(kInsStatusNames, value); }

}  // namespace brickyard::drivers
