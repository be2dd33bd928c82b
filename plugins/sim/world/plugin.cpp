// sim.world: reads a track file and publishes the static world (track, banking, walls, pylons)
// that every other simulator node builds its geometry from.
#include <brickyard/plugin.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "bank_params.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

std::vector<Pylon> parse_pylons(const std::string& text) {
  auto j = nlohmann::json::parse(text);
  if (!j.is_array()) throw BadInput("parameter 'pylons': must be an array");
  std::vector<Pylon> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string at = "parameter 'pylons' /" + std::to_string(i);
    if (!j[i].is_object()) throw BadInput(at + ": must be an object {s, d, radius, height}");
    Pylon p;
    for (auto it = j[i].begin(); it != j[i].end(); ++it) {
      if (!it->is_number()) throw BadInput(at + "/" + it.key() + ": must be a number");
      double v = it->get<double>();
      if (it.key() == "s") p.s = v;
      else if (it.key() == "d") p.d = v;
      else if (it.key() == "radius") p.radius = v;
      else if (it.key() == "height") p.height = v;
      else throw BadInput(at + "/" + it.key() + ": unknown key (s, d, radius, height)");
    }
    if (!j[i].contains("s") || !j[i].contains("d")) throw BadInput(at + ": needs s and d");
    if (p.radius <= 0 || p.height <= 0) throw BadInput(at + ": radius and height must be positive");
    out.push_back(p);
  }
  return out;
}

// The simulator's road is banked in its turns by default (IMS: 9 deg 12 min), unlike the map's.
track::BankSpec default_bank() {
  track::BankSpec b;
  b.mode = "curvature";
  b.degrees = 9.2;
  return b;
}

struct Settings {
  std::string track = "tracks/IMS.csv";
  std::string name;
  track::BankSpec bank = default_bank();
  std::string outer_side = "auto";
  bool outer_wall = true;
  double outer_wall_offset_m = 0.0;
  bool inner_wall = false;
  double inner_wall_offset_m = 2.0, wall_height_m = 1.2;
  std::string pylons = "[]";  // parsed in configure, after the track is read
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("track", &Settings::track).doc("centre-line file: x_m,y_m,w_tr_right_m,w_tr_left_m");
  b.bind("name", &Settings::name).doc("track name; default: the file's stem");
  plugins::bind_bank(b, &Settings::bank);
  b.bind("outer_side", &Settings::outer_side).one_of({"auto", "left", "right"})
      .doc("side of the outer wall; auto: the outside of the loop");
  b.bind("outer_wall", &Settings::outer_wall);
  b.bind("outer_wall_offset_m", &Settings::outer_wall_offset_m).in_unit("m").range(0, 100).doc("beyond the track edge");
  b.bind("inner_wall", &Settings::inner_wall);
  b.bind("inner_wall_offset_m", &Settings::inner_wall_offset_m).in_unit("m").range(0, 100);
  b.bind("wall_height_m", &Settings::wall_height_m).in_unit("m").range(0.1, 100);
  b.bind_json("pylons", &Settings::pylons).doc("[{\"s\": m, \"d\": m, \"radius\": 0.2, \"height\": 0.7}, ...]");
  b.declare(ParamSpec::number("rate_hz", 1.0).in_unit("Hz").range(0.01, 1000));  // the host's trigger only
  return b;
}

struct Ports {
  Output<msgs::TrackWorld> world;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("world", &Ports::world).doc("the static world, republished at rate_hz for late joiners");
  return b;
}

class World : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.world", "1.0.0")
        .describe("The simulated world: a track file (TUM racetrack-database format), banking, walls and pylons")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const std::string path = ctx.find_file(s.track);
    WorldSpec w;
    try {
      w.line = load_centerline_csv(path);
    } catch (const TrackFileError& e) {
      throw BadInput(std::string("track file ") + e.what());
    }
    for (const auto& note : w.line.notes) ctx.log(LogLevel::info, note);  // a bridge
    w.name = s.name.empty() ? std::filesystem::path(path).stem().string() : s.name;
    try {
      w.bank = bank_profile(w.line, s.bank);
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("parameter 'bank_mode': ") + e.what());
    }
    std::string outer = s.outer_side;
    if (outer == "auto") outer = counter_clockwise(w.line) ? "right" : "left";
    const bool outer_left = outer == "left";
    w.walls.height = s.wall_height_m;
    auto set_side = [&](bool left, bool on, double off) {
      (left ? w.walls.left : w.walls.right) = on;
      (left ? w.walls.left_offset : w.walls.right_offset) = off;
    };
    set_side(outer_left, s.outer_wall, s.outer_wall_offset_m);
    set_side(!outer_left, s.inner_wall, s.inner_wall_offset_m);
    w.pylons = parse_pylons(s.pylons);
    track_ = std::make_unique<Track>(std::move(w));
    for (const auto& q : track_->spec().pylons) {
      Frenet f = track_->at(q.s, q.d);
      if (q.d > track_->width_left(f.seg, f.u) || q.d < -track_->width_right(f.seg, f.u))
        ctx.log(LogLevel::warn, "pylon at s=" + std::to_string(q.s) + " d=" + std::to_string(q.d) + " stands off the road");
    }
    msg_ = std::make_shared<msgs::TrackWorld>(to_message(*track_));
    msg_->header().frame_id("map");
    io_ = ports().connect(ctx);
    ctx.log(LogLevel::info, "track '" + track_->spec().name + "' from " + path + ": " + std::to_string(track_->size()) +
                                " points, " + std::to_string(track_->length()) + " m");
  }

  void step(Context& ctx) override {
    // The world is static: the same object every time (readers in this process share it).
    if (published_ == 0) msg_->header().stamp_ns(ctx.now_ns());
    io_.world.publish(std::shared_ptr<const msgs::TrackWorld>(msg_));
    ++published_;
  }

  void deactivate(Context& ctx) override {
    ctx.metric("length_m", track_->length());
    ctx.metric("points", static_cast<double>(track_->size()));
  }

 private:
  std::unique_ptr<Track> track_;
  std::shared_ptr<msgs::TrackWorld> msg_;
  Ports io_;
  std::uint64_t published_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(World)
