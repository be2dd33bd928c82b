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

class World : public Plugin {
 public:
  static Manifest manifest() {
    return plugins::with_bank_params(
               Manifest("sim.world", "1.0.0")
                   .describe("The simulated world: a track file (TUM racetrack-database format), banking, walls and pylons")
                   .output<msgs::TrackWorld>("world", "the static world, republished at rate_hz for late joiners")
                   .param(ParamSpec::string("track", "tracks/IMS.csv").doc("centre-line file: x_m,y_m,w_tr_right_m,w_tr_left_m"))
                   .param(ParamSpec::string("name", "").doc("track name; default: the file's stem")),
               "curvature", 9.2)
        .param(ParamSpec::string("outer_side", "auto").one_of({"auto", "left", "right"})
                   .doc("side of the outer wall; auto: the outside of the loop"))
        .param(ParamSpec::boolean("outer_wall", true))
        .param(ParamSpec::number("outer_wall_offset_m", 0.0).in_unit("m").at_least(0).doc("beyond the track edge"))
        .param(ParamSpec::boolean("inner_wall", false))
        .param(ParamSpec::number("inner_wall_offset_m", 2.0).in_unit("m").at_least(0))
        .param(ParamSpec::number("wall_height_m", 1.2).in_unit("m").at_least(0.1))
        .param(ParamSpec::json("pylons", "[]").doc("[{\"s\": m, \"d\": m, \"radius\": 0.2, \"height\": 0.7}, ...]"))
        .param(ParamSpec::number("rate_hz", 1.0).in_unit("Hz").at_least(0.01))
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    const std::string path = ctx.find_file(p.string("track"));
    WorldSpec w;
    try {
      w.line = load_centerline_csv(path);
    } catch (const TrackFileError& e) {
      throw BadInput(std::string("track file ") + e.what());
    }
    w.name = p.string("name").empty() ? std::filesystem::path(path).stem().string() : p.string("name");
    w.bank = bank_profile(w.line, plugins::read_bank_params(p));
    std::string outer = p.string("outer_side");
    if (outer == "auto") outer = counter_clockwise(w.line) ? "right" : "left";
    const bool outer_left = outer == "left";
    w.walls.height = p.number("wall_height_m");
    auto set_side = [&](bool left, bool on, double off) {
      (left ? w.walls.left : w.walls.right) = on;
      (left ? w.walls.left_offset : w.walls.right_offset) = off;
    };
    set_side(outer_left, p.boolean("outer_wall"), p.number("outer_wall_offset_m"));
    set_side(!outer_left, p.boolean("inner_wall"), p.number("inner_wall_offset_m"));
    w.pylons = parse_pylons(p.json("pylons"));
    track_ = std::make_unique<Track>(std::move(w));
    for (const auto& q : track_->spec().pylons) {
      Frenet f = track_->at(q.s, q.d);
      if (q.d > track_->width_left(f.seg, f.u) || q.d < -track_->width_right(f.seg, f.u))
        ctx.log(LogLevel::warn, "pylon at s=" + std::to_string(q.s) + " d=" + std::to_string(q.d) + " stands off the road");
    }
    msg_ = std::make_shared<msgs::TrackWorld>(to_message(*track_));
    msg_->header().frame_id("map");
    out_ = ctx.output<msgs::TrackWorld>("world");
    ctx.log(LogLevel::info, "track '" + track_->spec().name + "' from " + path + ": " + std::to_string(track_->size()) +
                                " points, " + std::to_string(track_->length()) + " m");
  }

  void step(Context& ctx) override {
    // The world is static: the same object every time (readers in this process share it).
    if (published_ == 0) msg_->header().stamp_ns(ctx.now_ns());
    out_.publish(std::shared_ptr<const msgs::TrackWorld>(msg_));
    ++published_;
  }

  void deactivate(Context& ctx) override {
    ctx.metric("length_m", track_->length());
    ctx.metric("points", static_cast<double>(track_->size()));
  }

 private:
  std::unique_ptr<Track> track_;
  std::shared_ptr<msgs::TrackWorld> msg_;
  Output<msgs::TrackWorld> out_;
  std::uint64_t published_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(World)
