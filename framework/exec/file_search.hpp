#pragma once
// Files named in parameters (Context::find_file): an absolute path as it is; a relative one next
// to the graph file, in the working directory, in $BRICKYARD_DATA_PATH, then in
// <prefix>/share/brickyard/data (the build tree has a link to data/).
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::fw {

// $BRICKYARD_DATA_PATH's folders, then <prefix>/share/brickyard/data.
std::vector<std::string> data_dirs();

// The file's path; throws BadInput naming every place it looked. graph_file: "" when the graph
// came from no file.
std::string find_data_file(const std::string& graph_file, std::string_view path);

}  // namespace brickyard::fw
