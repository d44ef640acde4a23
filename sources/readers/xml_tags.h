// The smallest XML subset the Voreen .vvd (and VTK .vti) headers need: finding start tags by
// name and reading their attributes. No DTDs, no namespaces, no validation of nesting.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "format/error.h"

namespace voxlink::convert {

struct XmlTag {
  std::string name;
  std::map<std::string, std::string> attributes;  // entity references decoded
  size_t begin = 0;                               // offset of '<'
  size_t end = 0;                                 // offset just after '>'
  bool selfClosing = false;

  const std::string* attribute(const std::string& key) const {
    const auto it = attributes.find(key);
    return it == attributes.end() ? nullptr : &it->second;
  }
};

// The first start tag named `name` in xml[from, until), skipping comments and <?...?>.
// kCorrupt (naming `file`) when a tag is malformed.
Result<std::optional<XmlTag>> findTag(std::string_view xml, std::string_view name,
                                      const std::string& file, size_t from = 0,
                                      size_t until = std::string_view::npos);

// Offset of the end tag </name> after `from`, or npos.
size_t findEndTag(std::string_view xml, std::string_view name, size_t from);

}  // namespace voxlink::convert
