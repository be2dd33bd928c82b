// The vehicle interface's CAN work at the command rate (issue 43), one thread: every millisecond
// the five commands of the car's DBC (data/vehicle_interface/CAN1-INDY-V14.dbc) — brake 1400,
// accelerator 1401, steering 1402, gear 1403, race-control report 1404 — packed from values by
// name and unpacked again (as the simulator reads them back), then the five frames through one
// cannelloni datagram and back. The baseline does the same packing and unpacking with code
// written by hand for these five messages (shifts and masks, as a DBC code generator emits),
// measured in the same run. Printed: time per tick and its share of one core at 1 kHz.
// Exits 1 when the two pack other bytes for the same commands (checked on every 97th tick) or
// the datagram does not bring the five frames back as sent.
// usage: bench_can [--quick]
#include "vehicle_interface/common/can_message.hpp"
#include "vehicle_interface/common/cannelloni.hpp"
#include "vehicle_interface/common/dbc.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace brickyard::vehicle_interface;

namespace {

using Clock = std::chrono::steady_clock;

struct Commands {
  double brake_kpa, pedal_percent, steering_deg;
  int counter, gear, ct_state;
};

Commands commands_at(int tick) {
  const double t = tick * 1e-3;
  return {1500 + 1000 * std::sin(t), 40 + 30 * std::sin(0.7 * t), 200 * std::sin(0.3 * t), tick % 256, 1 + tick % 6, tick % 9};
}

// The hand-written baseline: the same rounding and clamping to the signals' carried ranges.
int64_t clamp_round(double x, int64_t low, int64_t high) { return std::clamp<int64_t>(std::llround(x), low, high); }

void put_le(uint8_t* d, int start, int bits, uint64_t raw) {
  for (int i = 0; i < bits; ++i)
    if ((raw >> i) & 1u) d[(start + i) / 8] |= static_cast<uint8_t>(1u << ((start + i) % 8));
}

double hand_written_tick(const Commands& c, uint8_t frames[5][8]) {
  std::memset(frames, 0, 5 * 8);
  put_le(frames[0], 0, 13, static_cast<uint64_t>(clamp_round(c.brake_kpa, 0, 8191)));
  put_le(frames[0], 16, 8, static_cast<uint64_t>(c.counter));
  put_le(frames[1], 0, 16, static_cast<uint64_t>(clamp_round(c.pedal_percent / 0.01, -15000, 32767)) & 0xFFFF);
  put_le(frames[1], 16, 8, static_cast<uint64_t>(c.counter));
  put_le(frames[2], 0, 11, static_cast<uint64_t>(clamp_round(c.steering_deg / 0.5, -1024, 1023)) & 0x7FF);
  put_le(frames[2], 16, 8, static_cast<uint64_t>(c.counter));
  frames[3][0] = static_cast<uint8_t>(c.gear);
  put_le(frames[4], 24, 16, static_cast<uint64_t>(c.ct_state));
  put_le(frames[4], 40, 8, static_cast<uint64_t>(c.counter % 10));
  // Unpacked again: the values a reader of the frames gets.
  const int64_t steering = static_cast<int16_t>(static_cast<uint16_t>((frames[2][0] | frames[2][1] << 8) << 5)) >> 5;
  const int64_t pedal = static_cast<int16_t>(frames[1][0] | frames[1][1] << 8);
  const int64_t brake = (frames[0][0] | frames[0][1] << 8) & 0x1FFF;
  return steering * 0.5 + pedal * 0.01 + brake + frames[3][0] + frames[4][3] + frames[4][5];
}

double dbc_tick(const Commands& c, const DbcMessage* const m[5], std::vector<CanFrame>& frames) {
  const SignalValues values[5] = {
      {{"brake_pressure_cmd", c.brake_kpa}, {"brk_pressure_cmd_counter", c.counter}},
      {{"acc_pedal_cmd", c.pedal_percent}, {"acc_pedal_cmd_counter", c.counter}},
      {{"steering_motor_ang_cmd", c.steering_deg}, {"steering_motor_cmd_counter", c.counter}},
      {{"desired_gear", c.gear}},
      {{"ct_state", c.ct_state}, {"ct_state_rolling_counter", c.counter % 10}}};
  frames.clear();
  double sum = 0;
  for (int i = 0; i < 5; ++i) {
    frames.push_back(pack_message(*m[i], values[i]).frame);
    for (const auto& [name, value] : unpack_message(*m[i], frames.back()).values) sum += value;
  }
  return sum;
}

template <class F> double ns_per_tick(int ticks, F&& tick) {
  const auto t0 = Clock::now();
  for (int i = 0; i < ticks; ++i) tick(i);
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / ticks;
}

void print_row(const char* what, double ns) { std::printf("  %-52s %9.0f ns a tick   %6.3f %% of a core at 1 kHz\n", what, ns, ns / 1e4); }

// The ticks on which ours and the hand-written code pack other bytes (every `step`th tick checked).
int ticks_packed_apart(int ticks, int step, const DbcMessage* const m[5]) {
  int apart = 0;
  std::vector<CanFrame> ours;
  uint8_t hand[5][8];
  for (int i = 0; i < ticks; i += step) {
    hand_written_tick(commands_at(i), hand);
    dbc_tick(commands_at(i), m, ours);
    for (int k = 0; k < 5; ++k) apart += std::memcmp(ours[k].data.data(), hand[k], 8) != 0 ? 1 : 0;
  }
  return apart;
}
}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const int ticks = quick ? 20000 : 200000;
  const DbcReadResult dbc = load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  if (!dbc.ok()) {
    std::fprintf(stderr, "bench_can: %s\n", dbc.errors.front().text().c_str());
    return 1;
  }
  const DbcMessage* m[5] = {dbc.database->find(1400, false), dbc.database->find(1401, false), dbc.database->find(1402, false),
                            dbc.database->find(1403, false), dbc.database->find(1404, false)};
  volatile double sink = 0;
  std::vector<CanFrame> frames, received;
  uint8_t hand[5][8];
  uint8_t sequence = 0;
  CannelloniDecoder decoder;
  const double baseline = ns_per_tick(ticks, [&](int i) { sink = sink + hand_written_tick(commands_at(i), hand); });
  const double ours = ns_per_tick(ticks, [&](int i) { sink = sink + dbc_tick(commands_at(i), m, frames); });
  const double with_udp = ns_per_tick(ticks, [&](int i) {
    sink = sink + dbc_tick(commands_at(i), m, frames);
    const CannelloniEncoding e = encode_cannelloni(frames, sequence);
    received.clear();
    decoder.decode(e.datagrams[0].data(), e.datagrams[0].size(), received);
  });
  std::printf("bench_can: the five commands (1400-1404) packed and unpacked every tick, %d ticks\n", ticks);
  print_row("baseline: hand-written for these five messages", baseline);
  print_row("ours: DBC pack_message + unpack_message", ours);
  print_row("ours, and the frames through a cannelloni datagram", with_udp);
  if (const int apart = ticks_packed_apart(ticks, 97, m))
    return std::fprintf(stderr, "bench_can: %d frames packed apart from the hand-written code's\n", apart), 1;
  if (received != frames) return std::fprintf(stderr, "bench_can: the datagram brought other frames back\n"), 1;
  return 0;
}
