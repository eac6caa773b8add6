// SPDX-License-Identifier: MIT
// A tiny XML reader for the writer tests: checks that tags are balanced and
// extracts elements with their attributes and text. Enough for the VTK XML
// files sadr writes (no CDATA, no comments, no entities in text), including
// raw appended binary data (read_vtk, values).
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sadr::orchestrator::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;               ///< character data directly inside the element
  std::vector<std::string> path;  ///< names of the enclosing elements, outermost first
};

/// Parses `xml`; throws std::runtime_error on unbalanced or malformed tags.
inline std::vector<XmlElement> parse_xml(const std::string& xml) {
  std::vector<XmlElement> done;
  std::vector<XmlElement> open;
  std::size_t i = 0;
  while (i < xml.size()) {
    if (xml[i] != '<') {
      const std::size_t next = xml.find('<', i);
      const std::string text = xml.substr(i, next - i);
      if (!open.empty())
        open.back().text += text;
      else if (text.find_first_not_of(" \n\r\t") != std::string::npos)
        throw std::runtime_error("text outside the root element");
      i = next == std::string::npos ? xml.size() : next;
      continue;
    }
    const std::size_t close = xml.find('>', i);
    if (close == std::string::npos) throw std::runtime_error("unterminated tag");
    std::string tag = xml.substr(i + 1, close - i - 1);
    i = close + 1;
    if (tag.rfind("?", 0) == 0) continue;  // declaration
    if (tag.rfind("/", 0) == 0) {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back().name != name)
        throw std::runtime_error("unbalanced closing tag </" + name + ">");
      done.push_back(open.back());
      open.pop_back();
      continue;
    }
    const bool self_closing = !tag.empty() && tag.back() == '/';
    if (self_closing) tag.pop_back();
    XmlElement e;
    std::istringstream in(tag);
    in >> e.name;
    std::string rest;
    std::getline(in, rest);
    std::size_t p = 0;
    while ((p = rest.find('=', p)) != std::string::npos) {
      std::size_t k = p;
      while (k > 0 && rest[k - 1] != ' ') --k;
      const std::string key = rest.substr(k, p - k);
      if (p + 1 >= rest.size() || rest[p + 1] != '"')
        throw std::runtime_error("unquoted attribute");
      const std::size_t end = rest.find('"', p + 2);
      if (end == std::string::npos) throw std::runtime_error("unterminated attribute");
      e.attributes[key] = rest.substr(p + 2, end - p - 2);
      p = end + 1;
    }
    for (const auto& o : open) e.path.push_back(o.name);
    if (self_closing)
      done.push_back(e);
    else
      open.push_back(e);
  }
  if (!open.empty()) throw std::runtime_error("unclosed element <" + open.back().name + ">");
  return done;
}

/// Numbers in an element's text.
inline std::vector<double> numbers(const XmlElement& e) {
  std::vector<double> out;
  std::istringstream in(e.text);
  double v = 0;
  while (in >> v) out.push_back(v);
  return out;
}

/// The DataArray named `name` (throws if absent).
inline const XmlElement& data_array(const std::vector<XmlElement>& all, const std::string& name) {
  for (const auto& e : all) {
    if (e.name == "DataArray" && e.attributes.count("Name") && e.attributes.at("Name") == name)
      return e;
  }
  throw std::runtime_error("no DataArray named " + name);
}

/// A VTK XML file: its elements, and the raw appended data (the bytes after the '_' of
/// <AppendedData encoding="raw">; empty for an ASCII file).
struct VtkDoc {
  std::vector<XmlElement> xml;
  std::string raw;
};

inline VtkDoc read_vtk(const std::string& bytes) {
  const std::string open_tag = "<AppendedData encoding=\"raw\">";
  const std::size_t a = bytes.find(open_tag);
  if (a == std::string::npos) return {parse_xml(bytes), {}};
  const std::size_t underscore = bytes.find('_', a + open_tag.size());
  const std::size_t close = bytes.rfind("</AppendedData>");
  if (underscore == std::string::npos || close == std::string::npos || close < underscore)
    throw std::runtime_error("malformed AppendedData");
  // The raw block ends with the newline and indentation before </AppendedData>.
  std::size_t end = close;
  while (end > underscore + 1 && (bytes[end - 1] == ' ' || bytes[end - 1] == '\n')) --end;
  VtkDoc d;
  d.xml =
      parse_xml(bytes.substr(0, a) + bytes.substr(close + std::string("</AppendedData>").size()));
  d.raw = bytes.substr(underscore + 1, end - underscore - 1);
  return d;
}

/// The values of the DataArray `name`, ASCII or appended raw (UInt64 block header;
/// types UInt8, UInt64, Int64, Float64), as doubles.
inline std::vector<double> values(const VtkDoc& d, const std::string& name) {
  const XmlElement& e = data_array(d.xml, name);
  if (e.attributes.count("format") && e.attributes.at("format") == "appended") {
    const std::size_t off = std::stoull(e.attributes.at("offset"));
    std::uint64_t bytes = 0;
    if (off + sizeof bytes > d.raw.size()) throw std::runtime_error("offset past the data");
    std::memcpy(&bytes, d.raw.data() + off, sizeof bytes);
    const char* p = d.raw.data() + off + sizeof bytes;
    if (off + sizeof bytes + bytes > d.raw.size()) throw std::runtime_error("block past the data");
    const std::string type = e.attributes.at("type");
    std::vector<double> out;
    auto read = [&](auto zero) {
      using T = decltype(zero);
      if (bytes % sizeof(T) != 0) throw std::runtime_error("block size not a multiple");
      for (std::size_t k = 0; k < bytes / sizeof(T); ++k) {
        T v;
        std::memcpy(&v, p + k * sizeof(T), sizeof(T));
        out.push_back(static_cast<double>(v));
      }
    };
    if (type == "Float64")
      read(double{});
    else if (type == "UInt64")
      read(std::uint64_t{});
    else if (type == "Int64")
      read(std::int64_t{});
    else if (type == "UInt8")
      read(std::uint8_t{});
    else
      throw std::runtime_error("unexpected type " + type);
    return out;
  }
  return numbers(e);
}

}  // namespace sadr::orchestrator::test
