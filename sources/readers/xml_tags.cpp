#include "sources/readers/xml_tags.h"

#include <algorithm>
#include <cctype>

namespace voxlink::convert {
namespace {

bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
         c == ':';
}

std::string decodeEntities(std::string_view text) {
  static const std::pair<std::string_view, char> kEntities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    bool replaced = false;
    if (text[i] == '&') {
      for (const auto& [entity, c] : kEntities) {
        if (text.substr(i, entity.size()) == entity) {
          out += c;
          i += entity.size() - 1;
          replaced = true;
          break;
        }
      }
    }
    if (!replaced) out += text[i];
  }
  return out;
}

Result<XmlTag> parseTag(std::string_view xml, size_t begin, const std::string& file) {
  XmlTag tag;
  tag.begin = begin;
  size_t i = begin + 1;
  while (i < xml.size() && isNameChar(xml[i])) tag.name += xml[i++];
  const auto fail = [&](const char* what) {
    return makeError(ErrorCode::kCorrupt, file, ": XML tag <", tag.name, "> at byte ", begin, ": ",
                     what);
  };
  while (true) {
    while (i < xml.size() && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
    if (i >= xml.size()) return fail("not closed");
    if (xml[i] == '>') {
      tag.end = i + 1;
      return tag;
    }
    if (xml[i] == '/' && i + 1 < xml.size() && xml[i + 1] == '>') {
      tag.selfClosing = true;
      tag.end = i + 2;
      return tag;
    }
    std::string key;
    while (i < xml.size() && isNameChar(xml[i])) key += xml[i++];
    while (i < xml.size() && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
    if (key.empty() || i >= xml.size() || xml[i] != '=') return fail("malformed attribute");
    ++i;
    while (i < xml.size() && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
    if (i >= xml.size() || (xml[i] != '"' && xml[i] != '\''))
      return fail("attribute value not quoted");
    const char quote = xml[i++];
    const size_t close = xml.find(quote, i);
    if (close == std::string_view::npos) return fail("attribute value not closed");
    tag.attributes[key] = decodeEntities(xml.substr(i, close - i));
    i = close + 1;
  }
}

}  // namespace

Result<std::optional<XmlTag>> findTag(std::string_view xml, std::string_view name,
                                      const std::string& file, size_t from, size_t until) {
  until = std::min(until, xml.size());
  size_t i = from;
  while (true) {
    i = xml.find('<', i);
    if (i == std::string_view::npos || i >= until) return std::optional<XmlTag>();
    if (xml.substr(i, 4) == "<!--") {
      const size_t close = xml.find("-->", i + 4);
      if (close == std::string_view::npos)
        return makeError(ErrorCode::kCorrupt, file, ": XML comment not closed");
      i = close + 3;
      continue;
    }
    const std::string_view rest = xml.substr(i + 1);
    if (rest.starts_with(name) && rest.size() > name.size() && !isNameChar(rest[name.size()])) {
      VOXLINK_ASSIGN_OR_RETURN(XmlTag tag, parseTag(xml, i, file));
      return std::optional<XmlTag>(std::move(tag));
    }
    ++i;
  }
}

size_t findEndTag(std::string_view xml, std::string_view name, size_t from) {
  const std::string close = "</" + std::string(name);
  size_t i = from;
  while ((i = xml.find(close, i)) != std::string_view::npos) {
    const size_t after = i + close.size();
    if (after < xml.size() &&
        (xml[after] == '>' || std::isspace(static_cast<unsigned char>(xml[after]))))
      return i;
    i = after;
  }
  return std::string_view::npos;
}

}  // namespace voxlink::convert
