#pragma once
// vehicle_interface.raptor_dbw's messages and metrics from the interface's state. Plugin-side (SDK).
#include <brickyard/context.hpp>
#include <brickyard/msgs/RaceControl.h>
#include <brickyard/msgs/VehicleStatus.h>

#include "vehicle_interface/bus/can_bus.hpp"
#include "vehicle_interface/common/raptor_interface.hpp"

#include <numbers>
#include <string>

namespace brickyard::vehicle_interface {

inline msgs::VehicleStatus status_message(const RaptorInterface& iface, std::int64_t now_ns, std::uint32_t seq) {
  const DbwReports& r = iface.reports();
  msgs::VehicleStatus m;
  m.header().stamp_ns(now_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  m.steer_motor_deg(r.steer_motor_deg);
  m.steer(r.steer_motor_deg / iface.mapping().maps().steering_ratio * std::numbers::pi / 180);
  m.brake_pressure_front_kpa(r.brake_front_kpa);
  m.brake_pressure_rear_kpa(r.brake_rear_kpa);
  m.accelerator_pct(r.accelerator_pct);
  m.gear(static_cast<std::int16_t>(r.gear));
  m.desired_gear(static_cast<std::int16_t>(iface.setpoint().gear));
  m.engine_rpm(r.engine_rpm);
  m.speed(r.speed);
  m.gear_shift_status(static_cast<std::uint8_t>(r.gear_shift_status));
  m.engine_running(r.engine_running);
  m.diagnostic_bits(r.diagnostic_bits);
  m.motec_warning(static_cast<std::uint8_t>(r.motec_warning));
  m.interface_state(static_cast<std::uint8_t>(iface.watchdog().state()));
  m.interface_state_name(dbw_state_name(iface.watchdog().state()));
  m.stale_reports(iface.monitor().silent_mask());
  m.counter_skips(static_cast<std::uint32_t>(iface.monitor().total_skips()));
  m.silences(static_cast<std::uint32_t>(iface.monitor().total_silences()));
  return m;
}

inline msgs::RaceControl race_control_message(const RaceControlMonitor& rc, std::int64_t now_ns, std::uint32_t seq) {
  const RaceControlState& st = rc.state();
  msgs::RaceControl m;
  m.header().stamp_ns(now_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  m.heard(st.heard);
  m.heartbeat_age_s(rc.heartbeat_age_s(now_ns));
  m.heartbeat(static_cast<std::uint8_t>(st.last.heartbeat));
  m.frames(static_cast<std::uint32_t>(st.frames));
  m.track_flag(static_cast<std::uint8_t>(st.track)), m.track_flag_name(track_flag_name(st.track));
  m.track_flag_code(static_cast<std::uint8_t>(st.last.track_code));
  m.vehicle_flag(static_cast<std::uint8_t>(st.vehicle)), m.vehicle_flag_name(vehicle_flag_name(st.vehicle));
  m.vehicle_flag_code(static_cast<std::uint8_t>(st.last.vehicle_code));
  m.target_speed(st.target_speed_mps), m.target_speed_mph(static_cast<std::uint8_t>(st.last.target_mph));
  m.lap(static_cast<std::uint8_t>(st.last.lap)), m.lap_distance(static_cast<std::uint16_t>(st.last.lap_distance_m));
  m.rank(static_cast<std::uint8_t>(st.last.rank));
  return m;
}

inline void report_race_control(Context& ctx, const RaceControlMonitor& rc, const BusCounts* bus) {
  const RaceControlState& st = rc.state();
  ctx.metric("race_control_frames", static_cast<double>(st.frames));
  ctx.metric("race_control_bad_frames", static_cast<double>(st.bad_frames));
  ctx.metric("race_control_heartbeat_repeats", static_cast<double>(st.heartbeat_repeats));
  ctx.metric("race_control_heartbeat_skips", static_cast<double>(st.heartbeat_skips));
  ctx.metric("race_control_losses", static_cast<double>(st.losses));
  ctx.metric("track_cond_ack", rc.track_ack()), ctx.metric("veh_sig_ack", rc.vehicle_ack());
  if (bus) ctx.metric("race_control_bus_datagrams_lost", static_cast<double>(bus->datagrams_lost));
}

inline void report_interface(Context& ctx, const RaptorInterface& iface, const BusCounts& bus) {
  auto metric = [&](const std::string& name, double v) { ctx.metric(name, v); };
  const InterfaceCounts& c = iface.counts();
  metric("commands", c.commands), metric("bad_commands", c.bad_commands), metric("frames_sent", c.frames_sent);
  metric("heartbeats", c.heartbeats), metric("clamped", c.clamped), metric("other_frames", c.other_frames);
  metric("path_stops", c.path_stops), metric("held_stops", c.held_stops);
  metric("bad_reports", c.bad_reports);
  for (RaptorMessage m : kRaptorReports) {
    const ReportCounts& r = iface.monitor().counts(m);
    const std::string n = raptor_name(m);
    metric(n + "_received", r.received), metric(n + "_silences", r.silences), metric(n + "_counter_skips", r.skips);
    metric(n + "_counter_missed", r.missed), metric(n + "_counter_repeats", r.repeats), metric(n + "_bad", r.bad);
  }
  const DbwWatchdog& w = iface.watchdog();
  metric("watchdog_trips", w.trips()), metric("watchdog_recoveries", w.recoveries());
  metric("longest_command_gap_s", w.longest_gap_s(ctx.now_s())), metric("last_command_s", w.last_command_s());
  metric("handed_over", w.state() == DbwState::handed_over ? 1 : 0);
  if (w.trips() > 0) metric("stop_distance_m", w.stop_distance_m()), metric("stop_time_s", w.stop_time_s());
  metric("gear_shifts", iface.shifter().shifts());
  metric("bus_frames_in", bus.frames_in), metric("bus_frames_out", bus.frames_out), metric("bus_frames_dropped", bus.frames_dropped);
  metric("bus_error_frames", bus.error_frames), metric("bus_datagrams_refused", bus.datagrams_refused);
  metric("bus_datagrams_lost", bus.datagrams_lost);
}

}  // namespace brickyard::vehicle_interface
