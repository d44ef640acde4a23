// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/xml_tags.h"

#include <algorithm>
#include <pugixml.hpp>

namespace voxlink::sources {
namespace {

// Escapes and CDATA as XML defines them; attribute whitespace kept as written (the readers
// split lists on any space), no DOCTYPE expansion: pugixml never reads external entities.
constexpr unsigned kParseOptions = pugi::parse_cdata | pugi::parse_escapes;

bool isText(const pugi::xml_node& node) {
  return node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata;
}

size_t offsetOf(const pugi::xml_node& node) {
  const ptrdiff_t at = node.offset_debug();
  return at < 0 ? XmlHeader::kNone : static_cast<size_t>(at);
}

XmlTag tagOf(const pugi::xml_node& node, bool followed) {
  XmlTag tag;
  tag.name = node.name();
  for (const pugi::xml_attribute& a : node.attributes()) tag.attributes[a.name()] = a.value();
  tag.begin = offsetOf(node);
  tag.textBegin = XmlHeader::kNone;
  for (const pugi::xml_node& child : node.children()) {
    tag.hasChildren = true;
    if (isText(child) && tag.textBegin == XmlHeader::kNone) {
      tag.textBegin = offsetOf(child);
      tag.text = child.value();
    }
  }
  tag.followed = followed;
  return tag;
}

// The elements in document order, walked without recursion (a hostile file may nest deeply).
std::vector<XmlTag> elementsOf(const pugi::xml_document& document) {
  std::vector<XmlTag> tags;
  std::vector<size_t> open;  // the elements around the current node
  pugi::xml_node node = document.first_child();
  while (node) {
    if (node.type() == pugi::node_element) {
      const bool followed = node.next_sibling() || (!open.empty() && tags[open.back()].followed);
      tags.push_back(tagOf(node, followed));
      if (node.first_child()) {
        open.push_back(tags.size() - 1);
        node = node.first_child();
        continue;
      }
      tags.back().subtreeEnd = tags.size();
    }
    while (node && !node.next_sibling()) {
      node = node.parent();
      if (node == document) return tags;
      tags[open.back()].subtreeEnd = tags.size();
      open.pop_back();
    }
    node = node.next_sibling();
  }
  return tags;
}

}  // namespace

XmlHeader::XmlHeader() : document_(std::make_unique<pugi::xml_document>()) {}
XmlHeader::XmlHeader(XmlHeader&&) noexcept = default;
XmlHeader& XmlHeader::operator=(XmlHeader&&) noexcept = default;
XmlHeader::~XmlHeader() = default;

Result<XmlHeader> XmlHeader::parse(std::string_view xml, const std::string& file,
                                   std::string_view rawElement, bool cutShort) {
  XmlHeader header;
  const pugi::xml_parse_result result =
      header.document_->load_buffer(xml.data(), xml.size(), kParseOptions, pugi::encoding_utf8);
  header.tags_ = elementsOf(*header.document_);
  if (result) return header;
  const size_t at = static_cast<size_t>(result.offset);
  if (!rawElement.empty()) {  // the raw bytes need not be XML: what came before them counts
    const size_t raw = header.find(rawElement);
    if (raw != kNone && header[raw].textBegin != kNone && at >= header[raw].textBegin)
      return header;
  }
  // pugixml reports the input's last byte when the input ends inside an element, and the
  // start of a tag or attribute that runs to the end (no '>' after it): both mean cut short.
  if (at + 1 >= xml.size() || xml.find('>', at) == std::string_view::npos) {
    if (cutShort) {
      header.endedOpen_ = true;
      return header;
    }
    // The outermost open element is the last one at the top level.
    size_t outer = 0;
    while (outer < header.size() && header[outer].subtreeEnd < header.size())
      outer = header[outer].subtreeEnd;
    if (outer >= header.size()) return makeError(ErrorCode::kTruncated, file, ": XML ends early");
    return makeError(ErrorCode::kTruncated, file, ": XML ends inside <", header[outer].name,
                     "> (truncated?)");
  }
  std::string after;  // the element the error follows, to say where it is
  for (const XmlTag& tag : header.tags_)
    if (tag.begin != kNone && tag.begin < at) after = cat(" after <", tag.name, ">");
  return makeError(ErrorCode::kCorrupt, file, ": XML at byte ", at, after, ": ",
                   result.description());
}

size_t XmlHeader::find(std::string_view name, size_t from, size_t until) const {
  for (size_t i = from; i < std::min(until, tags_.size()); ++i)
    if (tags_[i].name == name) return i;
  return kNone;
}

}  // namespace voxlink::sources
