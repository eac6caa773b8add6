// SPDX-License-Identifier: MIT
// gmsh's C API through dlopen (gmsh_dl.hpp). gmshc.h gives the functions' types only: nothing
// here links libgmsh.
#include "gmsh_dl.hpp"

#include <gmshc.h>

#include <mutex>
#include <stdexcept>

#include "dl_library.hpp"
#include "sadr/common/status.hpp"

namespace sadr::geometry::gmsh_dl {
namespace {

DlLibrary& library() {
  static DlLibrary lib({"libgmsh.so.4.8", "libgmsh.so"},
                       "the gmsh library (libgmsh.so.4.8; Debian: libgmsh4.8)", "reading a mesh");
  return lib;
}

#define SADR_GMSH(fn) library().symbol<decltype(fn)>(#fn)

std::string last_error() {
  char* text = nullptr;
  int ierr = 0;
  SADR_GMSH(gmshLoggerGetLastError)(&text, &ierr);
  std::string out = text ? text : "";
  if (text) SADR_GMSH(gmshFree)(text);
  return out.empty() ? "unknown gmsh error" : out;
}

void check(int ierr) {
  if (ierr != 0) throw std::runtime_error(last_error());
}

/// Copies a gmsh-allocated array into a vector and frees it.
template <class T>
std::vector<T> take(T* data, std::size_t n) {
  std::vector<T> v(data, data + n);
  if (data) SADR_GMSH(gmshFree)(data);
  return v;
}

std::string take_text(char* text) {
  std::string s = text ? text : "";
  if (text) SADR_GMSH(gmshFree)(text);
  return s;
}

}  // namespace

void initialize(int argc, char** argv, bool read_config_files) {
  int ierr = 0;
  SADR_GMSH(gmshInitialize)(argc, argv, read_config_files ? 1 : 0, &ierr);
  check(ierr);
}

void finalize() {
  int ierr = 0;
  SADR_GMSH(gmshFinalize)(&ierr);
}

void open(const std::string& path) {
  int ierr = 0;
  SADR_GMSH(gmshOpen)(path.c_str(), &ierr);
  check(ierr);
}

namespace option {
void setNumber(const std::string& name, double value) {
  int ierr = 0;
  SADR_GMSH(gmshOptionSetNumber)(name.c_str(), value, &ierr);
  check(ierr);
}
}  // namespace option

namespace logger {
void getLastError(std::string& error) {
  error = last_error();
}
}  // namespace logger

namespace model {

void getPhysicalGroups(vectorpair& dim_tags, int dim) {
  int* data = nullptr;
  std::size_t n = 0;
  int ierr = 0;
  SADR_GMSH(gmshModelGetPhysicalGroups)(&data, &n, dim, &ierr);
  const std::vector<int> flat = take(data, n);
  check(ierr);
  dim_tags.clear();
  for (std::size_t i = 0; i + 1 < flat.size(); i += 2) dim_tags.emplace_back(flat[i], flat[i + 1]);
}

void getPhysicalName(int dim, int tag, std::string& name) {
  char* text = nullptr;
  int ierr = 0;
  SADR_GMSH(gmshModelGetPhysicalName)(dim, tag, &text, &ierr);
  name = take_text(text);
  check(ierr);
}

void getEntitiesForPhysicalGroup(int dim, int tag, std::vector<int>& tags) {
  int* data = nullptr;
  std::size_t n = 0;
  int ierr = 0;
  SADR_GMSH(gmshModelGetEntitiesForPhysicalGroup)(dim, tag, &data, &n, &ierr);
  tags = take(data, n);
  check(ierr);
}

namespace mesh {

void getNodes(std::vector<std::size_t>& node_tags, std::vector<double>& coord,
              std::vector<double>& parametric_coord, int dim, int tag, bool include_boundary,
              bool return_parametric_coord) {
  std::size_t *tags = nullptr, n_tags = 0, n_coord = 0, n_param = 0;
  double *xyz = nullptr, *param = nullptr;
  int ierr = 0;
  SADR_GMSH(gmshModelMeshGetNodes)
  (&tags, &n_tags, &xyz, &n_coord, &param, &n_param, dim, tag, include_boundary ? 1 : 0,
   return_parametric_coord ? 1 : 0, &ierr);
  node_tags = take(tags, n_tags);
  coord = take(xyz, n_coord);
  parametric_coord = take(param, n_param);
  check(ierr);
}

void getElements(std::vector<int>& element_types,
                 std::vector<std::vector<std::size_t>>& element_tags,
                 std::vector<std::vector<std::size_t>>& node_tags, int dim, int tag) {
  int* types = nullptr;
  std::size_t n_types = 0;
  std::size_t **etags = nullptr, *etags_n = nullptr, etags_nn = 0;
  std::size_t **ntags = nullptr, *ntags_n = nullptr, ntags_nn = 0;
  int ierr = 0;
  SADR_GMSH(gmshModelMeshGetElements)
  (&types, &n_types, &etags, &etags_n, &etags_nn, &ntags, &ntags_n, &ntags_nn, dim, tag, &ierr);
  element_types = take(types, n_types);
  element_tags.clear();
  node_tags.clear();
  for (std::size_t i = 0; i < etags_nn; ++i) element_tags.push_back(take(etags[i], etags_n[i]));
  for (std::size_t i = 0; i < ntags_nn; ++i) node_tags.push_back(take(ntags[i], ntags_n[i]));
  for (void* p : {static_cast<void*>(etags), static_cast<void*>(etags_n), static_cast<void*>(ntags),
                  static_cast<void*>(ntags_n)}) {
    if (p) SADR_GMSH(gmshFree)(p);
  }
  check(ierr);
}

void getElementProperties(int element_type, std::string& name, int& dim, int& order, int& num_nodes,
                          std::vector<double>& local_node_coord, int& num_primary_nodes) {
  char* text = nullptr;
  double* local = nullptr;
  std::size_t n_local = 0;
  int ierr = 0;
  SADR_GMSH(gmshModelMeshGetElementProperties)
  (element_type, &text, &dim, &order, &num_nodes, &local, &n_local, &num_primary_nodes, &ierr);
  name = take_text(text);
  local_node_coord = take(local, n_local);
  check(ierr);
}

}  // namespace mesh
}  // namespace model
}  // namespace sadr::geometry::gmsh_dl
