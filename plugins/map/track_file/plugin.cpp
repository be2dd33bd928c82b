// map.track_file: the car's map from a track file — today's TUM racetrack-database format
// (x_m,y_m,w_tr_right_m,w_tr_left_m), later the output of a mapping run — published as a TrackMap
// (centre line, widths, banking; geometry only) for the planners and controllers. The car stack's
// counterpart of the simulator's sim.world, which it never reads.
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/plugin.hpp>

#include "bank_params.hpp"
#include "map_msg.hpp"
#include "track/banking.hpp"
#include "track/centre_line.hpp"
#include "track/narrow_place.hpp"
#include "track/track.hpp"
#include "vehicle_param.hpp"

#include <cmath>
#include <cstdio>

#include <filesystem>
#include <memory>

namespace {

using namespace brickyard;

struct Settings {
  std::string track = "tracks/IMS.csv";
  std::string name;
  track::BankSpec bank;  // flat unless the graph says otherwise
  double rate_hz = 1.0;
  std::string vehicle = plugins::default_vehicle_file;
};

struct LoadedMap {
  track::TrackGeometry geometry;
  double length = 0;
  std::string path;  // where the track file was found
};

// The map the parameters name, refused as configure would refuse it: the file read, the car fits
// it, its banking and its geometry built. `find` finds a file a parameter names.
template <class Find> LoadedMap load_map(const Settings& s, Find find) {
  LoadedMap m;
  m.path = find(s.track);
  track::TrackGeometry& g = m.geometry;
  try {
    g.line = track::load_centerline_csv(m.path);
  } catch (const track::TrackFileError& e) {
    throw BadInput(std::string("track file ") + e.what());
  }
  const vehicle::Vehicle car = plugins::read_vehicle_file(find(s.vehicle));
  if (const std::string where = track::narrower_than(g.line, 2 * car.half_width); !where.empty()) {
    char width[32];
    std::snprintf(width, sizeof width, "%.2f", 2 * car.half_width);
    throw BadInput("track file " + m.path + ": " + where + ", narrower than the car (" + width + " m, " + s.vehicle + ")");
  }
  g.name = s.name.empty() ? std::filesystem::path(m.path).stem().string() : s.name;
  try {
    g.bank = track::bank_profile(g.line, s.bank);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("parameter 'bank_mode': ") + e.what());
  }
  try {
    m.length = track::Track(g).length();  // the geometry the readers will build: refused here, not downstream
  } catch (const std::invalid_argument& e) {
    throw BadInput("track file " + m.path + ": " + e.what());
  }
  return m;
}

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("track", &Settings::track).doc("centre-line file: x_m,y_m,w_tr_right_m,w_tr_left_m");
  b.bind("name", &Settings::name).doc("track name; default: the file's stem");
  plugins::bind_bank(b, &Settings::bank);
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(0.01, 1000);
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car the map is for: a track narrower than it is refused");
  return b;
}

struct Ports {
  Output<msgs::TrackMap> map;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("map", &Ports::map).doc("the map, republished at rate_hz for late joiners");
  return b;
}

class TrackFileMap : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("map.track_file", "1.0.0")
        .describe("the car's map of the track from a track file: centre line, widths and banking (no obstacles)")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz")
        .check(&check);
  }

  // At validation, every file the parameters name read and checked, as configure will.
  static void check(const CheckView& v) {
    load_map(bindings().read(v.params()), [&](const std::string& f) { return v.find_file(f); });
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const LoadedMap m = load_map(s, [&](const std::string& f) { return ctx.find_file(f); });
    const track::TrackGeometry& g = m.geometry;
    for (const auto& note : g.line.notes) ctx.log(LogLevel::info, note);  // a bridge
    length_ = m.length;
    const std::string& path = m.path;
    points_ = g.line.x.size();
    msg_ = std::make_shared<msgs::TrackMap>(plugins::to_message(g));
    msg_->header().frame_id("map");
    io_ = ports().connect(ctx);
    ctx.log(LogLevel::info, "map '" + g.name + "' from " + path + ": " + std::to_string(points_) + " points, " +
                                std::to_string(length_) + " m");
  }

  void step(Context& ctx) override {
    // The map is static: the same object every time (readers in this process share it).
    if (published_ == 0) msg_->header().stamp_ns(ctx.now_ns());
    io_.map.publish(std::shared_ptr<const msgs::TrackMap>(msg_));
    ++published_;
  }

  void deactivate(Context& ctx) override {
    ctx.metric("length_m", length_);
    ctx.metric("points", static_cast<double>(points_));
  }

 private:
  std::shared_ptr<msgs::TrackMap> msg_;
  Ports io_;
  std::uint64_t published_ = 0;
  double length_ = 0;
  std::size_t points_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(TrackFileMap)
