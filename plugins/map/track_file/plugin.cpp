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

// The first place where the track is narrower than the car, as "s = X m: W m wide"; empty when
// the car fits everywhere. A map the car cannot drive is bad input, refused before anything runs.
std::string narrower_than(const track::CenterLine& c, double car_width) {
  double s = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (i > 0) s += std::hypot(c.x[i] - c.x[i - 1], c.y[i] - c.y[i - 1]);
    const double w = c.width_left[i] + c.width_right[i];
    if (w < car_width) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "at s = %.1f m (point %zu) it is %.2f m wide", s, i + 1, w);
      return buf;
    }
  }
  return {};
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

class TrackFileMap : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("map.track_file", "1.0.0")
        .describe("the car's map of the track from a track file: centre line, widths and banking (no obstacles)")
        .output<msgs::TrackMap>("map", "the map, republished at rate_hz for late joiners")
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const std::string path = ctx.find_file(s.track);
    track::TrackGeometry g;
    try {
      g.line = track::load_centerline_csv(path);
    } catch (const track::TrackFileError& e) {
      throw BadInput(std::string("track file ") + e.what());
    }
    for (const auto& note : g.line.notes) ctx.log(LogLevel::info, note);  // a bridge
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    if (const std::string where = narrower_than(g.line, 2 * car.half_width); !where.empty()) {
      char width[32];
      std::snprintf(width, sizeof width, "%.2f", 2 * car.half_width);
      throw BadInput("track file " + path + ": " + where + ", narrower than the car (" + width + " m, " + s.vehicle + ")");
    }
    g.name = s.name.empty() ? std::filesystem::path(path).stem().string() : s.name;
    try {
      g.bank = track::bank_profile(g.line, s.bank);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("parameter 'bank_mode': ") + e.what());
    }
    try {
      const track::Track t(g);  // the geometry the readers will build: refused here, not downstream
      length_ = t.length();
    } catch (const std::invalid_argument& e) {
      throw BadInput("track file " + path + ": " + e.what());
    }
    points_ = g.line.x.size();
    msg_ = std::make_shared<msgs::TrackMap>(plugins::to_message(g));
    msg_->header().frame_id("map");
    out_ = ctx.output<msgs::TrackMap>("map");
    ctx.log(LogLevel::info, "map '" + g.name + "' from " + path + ": " + std::to_string(points_) + " points, " +
                                std::to_string(length_) + " m");
  }

  void step(Context& ctx) override {
    // The map is static: the same object every time (readers in this process share it).
    if (published_ == 0) msg_->header().stamp_ns(ctx.now_ns());
    out_.publish(std::shared_ptr<const msgs::TrackMap>(msg_));
    ++published_;
  }

  void deactivate(Context& ctx) override {
    ctx.metric("length_m", length_);
    ctx.metric("points", static_cast<double>(points_));
  }

 private:
  std::shared_ptr<msgs::TrackMap> msg_;
  Output<msgs::TrackMap> out_;
  std::uint64_t published_ = 0;
  double length_ = 0;
  std::size_t points_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(TrackFileMap)
