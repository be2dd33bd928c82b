// sim.world: reads a track file and publishes the static world (track, banking, walls, pylons)
// that every other simulator node builds its geometry from.
#include <brickyard/plugin.hpp>

#include <filesystem>

#include "bank_params.hpp"
#include "sim/common/world_builder.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::string track = "tracks/IMS.csv";
  std::string name;
  track::BankSpec bank = default_bank();
  WallSettings walls;
  std::string pylons = "[]";  // parsed in configure, after the track is read
};

ParamBinding<Settings> bindings() {
  using W = WallSettings;
  ParamBinding<Settings> b;
  b.bind("track", &Settings::track).doc("centre-line file: x_m,y_m,w_tr_right_m,w_tr_left_m");
  b.bind("name", &Settings::name).doc("track name; default: the file's stem");
  plugins::bind_bank(b, &Settings::bank);
  b.bind("outer_side", &Settings::walls, &W::outer_side).one_of({"auto", "left", "right"})
      .doc("side of the outer wall; auto: the outside of the loop");
  b.bind("outer_wall", &Settings::walls, &W::outer_wall);
  b.bind("outer_wall_offset_m", &Settings::walls, &W::outer_wall_offset_m).in_unit("m").range(0, 100).doc("beyond the track edge");
  b.bind("inner_wall", &Settings::walls, &W::inner_wall);
  b.bind("inner_wall_offset_m", &Settings::walls, &W::inner_wall_offset_m).in_unit("m").range(0, 100);
  b.bind("wall_height_m", &Settings::walls, &W::wall_height_m).in_unit("m").range(0.1, 100);
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

// The world the settings describe, its track read from its file: for configure and at validation
// (Manifest::check). `notes`: what reading the file found worth saying (a bridge).
template <class Files> std::unique_ptr<Track> read_world(const Files& files, const Settings& s, std::vector<std::string>* notes) {
  const std::string path = files.find_file(s.track);
  CenterLine line;
  try {
    line = load_centerline_csv(path);
  } catch (const TrackFileError& e) {
    throw BadInput(std::string("track file ") + e.what());
  }
  if (notes) *notes = line.notes;
  std::string name = s.name.empty() ? std::filesystem::path(path).stem().string() : s.name;
  try {
    return std::make_unique<Track>(build_world(std::move(line), std::move(name), s.bank, s.walls, s.pylons));
  } catch (const WorldError& e) {
    throw BadInput(e.what());
  }
}

class World : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.world", "1.0.0")
        .describe("The simulated world: a track file (TUM racetrack-database format), banking, walls and pylons")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz")
        .check(&check);
  }

  static void check(const CheckView& v) { read_world(v, bindings().read(v.params()), nullptr); }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const std::string path = ctx.find_file(s.track);
    std::vector<std::string> notes;
    track_ = read_world(ctx, s, &notes);
    for (const auto& note : notes) ctx.log(LogLevel::info, note);  // a bridge
    for (const Pylon& q : pylons_off_road(*track_))
      ctx.log(LogLevel::warn, "pylon at s=" + std::to_string(q.s) + " d=" + std::to_string(q.d) + " stands off the road");
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
