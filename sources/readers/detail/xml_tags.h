// SPDX-License-Identifier: BSD-3-Clause
// The elements of an XML header (Voreen .vvd, VTK .vti), parsed by pugixml: names, attributes
// and the text each holds, in document order. The readers look elements up by name and range.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace pugi {
class xml_document;
}

namespace voxlink::sources {

struct XmlTag {
  std::string name;
  std::map<std::string, std::string> attributes;  // entity references decoded
  size_t begin = 0;                               // offset of the element's name in the file
  size_t subtreeEnd = 0;  // index of the first element after this one's descendants
  size_t textBegin = 0;   // offset in the file of the first text child; npos when none
  std::string_view text;  // that text (entities decoded), valid while the XmlHeader lives
  bool followed = false;  // a node follows the element, so it was closed
  bool hasChildren = false;

  const std::string* attribute(const std::string& key) const {
    const auto it = attributes.find(key);
    return it == attributes.end() ? nullptr : &it->second;
  }
};

class XmlHeader {
 public:
  static constexpr size_t kNone = std::string_view::npos;

  // Parses `xml`, a file's bytes or the first of them. A malformed header is kCorrupt, and one
  // that ends with elements open kTruncated, both naming `file` and the element; except
  //  - inside the text of the element named `rawElement`, which may hold any bytes (VTK's raw
  //    AppendedData): the elements before it are kept;
  //  - at the end of `xml` when `cutShort`: a header read in part, whose elements so far count.
  static Result<XmlHeader> parse(std::string_view xml, const std::string& file,
                                 std::string_view rawElement = {}, bool cutShort = false);

  XmlHeader(XmlHeader&&) noexcept;
  XmlHeader& operator=(XmlHeader&&) noexcept;
  ~XmlHeader();

  // Index of the first element named `name` in [from, until), or kNone.
  size_t find(std::string_view name, size_t from = 0, size_t until = kNone) const;
  const XmlTag& operator[](size_t i) const { return tags_[i]; }
  size_t size() const { return tags_.size(); }
  // True when the input ended with elements open (only when parse() was asked to allow it).
  bool endedOpen() const { return endedOpen_; }

 private:
  XmlHeader();
  std::unique_ptr<pugi::xml_document> document_;  // owns the text the tags point into
  std::vector<XmlTag> tags_;
  bool endedOpen_ = false;
};

}  // namespace voxlink::sources
