// SPDX-License-Identifier: MIT
// (private) The few gmsh API calls read_mesh makes, over gmsh's C API loaded with dlopen at the
// first mesh read: a program that links sadr::geometry but reads no mesh (every `sadr` command
// but those on a scene with a mesh) does not load libgmsh and its dozens of libraries (0.3 s
// and 45 MB at start-up). Same names and arguments as gmsh.h (4.8); an error throws
// std::runtime_error with gmsh's last error message.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace sadr::geometry::gmsh_dl {

using vectorpair = std::vector<std::pair<int, int>>;

/// Throws sadr::InvalidArgument naming the library when libgmsh cannot be loaded.
void initialize(int argc, char** argv, bool read_config_files);
void finalize();
void open(const std::string& path);

namespace option {
void setNumber(const std::string& name, double value);
}  // namespace option

namespace logger {
void getLastError(std::string& error);
}  // namespace logger

namespace model {
void getPhysicalGroups(vectorpair& dim_tags, int dim = -1);
void getPhysicalName(int dim, int tag, std::string& name);
void getEntitiesForPhysicalGroup(int dim, int tag, std::vector<int>& tags);
namespace mesh {
void getNodes(std::vector<std::size_t>& node_tags, std::vector<double>& coord,
              std::vector<double>& parametric_coord, int dim, int tag, bool include_boundary,
              bool return_parametric_coord);
void getElements(std::vector<int>& element_types,
                 std::vector<std::vector<std::size_t>>& element_tags,
                 std::vector<std::vector<std::size_t>>& node_tags, int dim, int tag);
void getElementProperties(int element_type, std::string& name, int& dim, int& order, int& num_nodes,
                          std::vector<double>& local_node_coord, int& num_primary_nodes);
}  // namespace mesh
}  // namespace model

}  // namespace sadr::geometry::gmsh_dl
