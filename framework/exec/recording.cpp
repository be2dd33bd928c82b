#include "exec/recording.hpp"

#include <brickyard/version.hpp>

#include <filesystem>

namespace brickyard::fw {

std::unique_ptr<Recorder> open_recording(const RunOptions& opt, const GraphDecl& g, bool sim) {
  auto r = std::make_unique<Recorder>(opt.record, opt.record_compression, opt.record_profile);
  r->set_metadata("graph", g.name);
  r->set_metadata("graph_file", g.file);
  r->set_metadata("clock", sim ? "sim" : "real");
  r->set_metadata("seed", std::to_string(opt.seed));
  r->set_metadata("process", opt.process.empty() ? "all" : opt.process);
  r->set_metadata("brickyard_version", BRICKYARD_SDK_VERSION);
  r->set_metadata("schema", "brickyard recording 1 (docs/recording.md)");
  return r;
}

nlohmann::json close_recording(Recorder& r) {
  r.close();
  std::error_code ec;
  const auto abs = std::filesystem::absolute(r.path(), ec);
  return {{"file", ec ? r.path() : abs.lexically_normal().string()}, {"messages", r.messages()}, {"bytes", r.bytes()}};
}

}  // namespace brickyard::fw
