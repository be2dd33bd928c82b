#include "exec/node_checks.hpp"

#include "exec/file_search.hpp"
#include "record/recorder.hpp"

#include <brickyard/context.hpp>

#include <map>

namespace brickyard::fw {
namespace {

class View : public CheckView {
 public:
  View(const ResolvedGraph& rg, const ResolvedNode& n) : rg_(rg), n_(n) {}

  const Params& params() const override { return n_.params; }

  const std::string& port_type(std::string_view port) const override {
    static const std::string none;
    const PortSpec* p = n_.plugin->manifest.port(std::string(port));
    if (!p) return none;
    if (!is_any_message_type(p->type_name)) return p->type_name;
    const auto& types = p->direction == PortDirection::input ? rg_.wire_types : rg_.output_types;
    auto it = types.find(n_.decl->name + "." + std::string(port));
    return it == types.end() ? none : it->second;
  }

  // The same self-contained IDL the port's Any handle gives at run time.
  const char* port_idl(std::string_view port) const override {
    const std::string& type = port_type(port);
    if (type.empty()) return nullptr;
    auto it = idl_.find(type);
    if (it == idl_.end()) {
      const char* idl = idl_text(type);
      if (!idl) return nullptr;
      it = idl_.emplace(type, omgidl_schema(idl)).first;
    }
    return it->second.c_str();
  }

  std::string find_file(std::string_view path) const override { return find_data_file(rg_.decl->file, path); }

 private:
  const ResolvedGraph& rg_;
  const ResolvedNode& n_;
  mutable std::map<std::string, std::string> idl_;
};

}  // namespace

std::vector<Diagnostic> run_node_checks(const ResolvedGraph& rg) {
  std::vector<Diagnostic> failed;
  for (const auto& n : rg.nodes) {
    const CheckFn check = n.plugin->manifest.checker;
    if (!check || !n.here) continue;  // (another process's node is checked there: its host has its files)
    const std::string who = "node '" + n.decl->name + "' (" + n.plugin->manifest.name + ")";
    try {
      check(View(rg, n));
    } catch (const BadInput& e) {
      failed.push_back({who, with_param_place(*rg.decl, n.decl->name, e.what())});
    } catch (const std::exception& e) {
      failed.push_back({who, std::string("its check failed: ") + e.what()});
    } catch (...) {
      failed.push_back({who, "its check failed: unknown exception"});
    }
  }
  return failed;
}

std::string with_param_place(const GraphDecl& g, const std::string& node, const std::string& what) {
  const std::string head = "parameter '";
  if (what.compare(0, head.size(), head) != 0) return what;
  const std::size_t end = what.find('\'', head.size());
  if (end == std::string::npos) return what;
  const std::string name = what.substr(head.size(), end - head.size());
  std::size_t at = end + 1;
  std::string inner;
  if (what.compare(at, 2, " /") == 0) {
    const std::size_t colon = what.find(':', at);
    if (colon == std::string::npos) return what;
    inner = what.substr(at + 1, colon - at - 1);
    if (inner.find(' ') != std::string::npos) return what;
    at = colon;
  }
  if (what.compare(at, 2, ": ") != 0) return what;
  return what + " (" + g.where("/nodes/" + pointer_escape(node) + "/params/" + pointer_escape(name) + inner) + ")";
}

}  // namespace brickyard::fw
