// SPDX-License-Identifier: MIT
// (private) A shared library loaded with dlopen at its first use, and its functions by name: how
// the mesh readers use gmsh (gmsh_dl.cpp) and assimp (mesh_io_obj.cpp) without linking them, so a
// program that reads no mesh does not load them.
#pragma once

#include <dlfcn.h>

#include <initializer_list>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "sadr/common/status.hpp"

namespace sadr::geometry {

class DlLibrary {
 public:
  /// `names`: the file names tried in order; `what`: the library and its Debian package, for the
  /// error ("the gmsh library (libgmsh.so.4.8; Debian: libgmsh4.8)"); `use`: what needs it.
  DlLibrary(std::initializer_list<const char*> names, std::string what, std::string use)
      : names_(names), what_(std::move(what)), use_(std::move(use)) {}

  /// The function `name` of type F; throws sadr::InvalidArgument when the library cannot be
  /// loaded or has no such function.
  template <class F>
  F* symbol(const char* name) {
    void* s = ::dlsym(handle(), name);
    if (!s) throw InvalidArgument(what_ + " has no function " + name);
    return reinterpret_cast<F*>(s);
  }

 private:
  void* handle() {
    std::call_once(once_, [this] {
      for (const char* name : names_) {
        handle_ = ::dlopen(name, RTLD_NOW | RTLD_LOCAL);
        if (handle_) return;
        const char* e = ::dlerror();
        if (error_.empty() && e) error_ = e;
      }
    });
    if (!handle_)
      throw InvalidArgument(use_ + " needs " + what_ + ", which cannot be loaded: " + error_);
    return handle_;
  }

  std::vector<const char*> names_;  ///< string literals
  std::string what_, use_, error_;
  std::once_flag once_;
  void* handle_ = nullptr;
};

}  // namespace sadr::geometry
