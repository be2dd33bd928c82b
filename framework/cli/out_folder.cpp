#include "cli/out_folder.hpp"

#include "cli/arguments.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace brickyard::fw::cli {
namespace {

namespace fs = std::filesystem;

// A summary.json that is not a run's (it names its result, and its graph or its writer) or a
// report.html that is not brickyard-report's is the user's, and the run refuses.
void refuse_foreign_files(const std::string& out) {
  const fs::path dir(out);
  std::error_code ec;
  if (fs::exists(dir / "summary.json", ec)) {
    bool ours = false;
    std::ifstream old(dir / "summary.json");
    try {
      const auto j = nlohmann::json::parse(old);
      ours = j.is_object() && j.contains("result") && (j.contains("graph") || j.contains("summary"));
    } catch (...) {
    }
    if (!ours) usage_error("--out " + out, (dir / "summary.json").string() + " was not written by brickyard: move it or use another folder");
  }
  if (fs::exists(dir / "report.html", ec)) {
    std::ifstream old(dir / "report.html");
    std::string head(300, '\0');
    old.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (head.find("<title>Brickyard run: ") == std::string::npos)
      usage_error("--out " + out, (dir / "report.html").string() + " was not written by brickyard-report: move it or use another folder");
  }
}

// The recording the folder's last run wrote (its summary says), or empty.
std::string own_recording_name(const fs::path& dir) {
  std::string ours_name;
  std::ifstream old(dir / "summary.json");
  try {
    const auto j = nlohmann::json::parse(old);
    if (j.contains("recording") && j["recording"].is_object()) ours_name = j["recording"].value("file", "");
  } catch (...) {
  }
  return ours_name;
}

}  // namespace

void prepare_out_folder(const std::string& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) usage_error("--out " + out, "cannot create the folder: " + ec.message());
  refuse_foreign_files(out);
}

void refuse_foreign_out_files(const std::string& out) { refuse_foreign_files(out); }

void clear_earlier_run(const std::string& out, const std::string& record) {
  const fs::path dir(out);
  std::error_code ec;
  const std::string ours_name = own_recording_name(dir);
  for (const char* name : {kOutRecording, "recording.db3"}) {  // (.db3: what --out wrote before MCAP)
    const fs::path rec = dir / name;
    if (!fs::exists(rec, ec)) continue;
    if (ours_name != name) usage_error("--out " + out, rec.string() + " was not written by --out (a --record file?): move it or use another folder");
    if (!record.empty() && fs::equivalent(record, rec, ec)) usage_error("--record " + record, "is the --out folder's own recording");
    fs::remove(rec, ec);
  }
  fs::remove(dir / "report.html", ec);
  fs::remove(dir / "summary.json", ec);
  // An earlier run here that was killed left its recording unclosed, under its temporary name.
  for (const char* end : {"", "-wal", "-shm"}) fs::remove(dir / (std::string(kOutRecording) + ".part" + end), ec);
}

}  // namespace brickyard::fw::cli
