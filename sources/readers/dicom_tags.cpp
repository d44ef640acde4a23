// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/dicom_tags.h"

#include <gdcmSequenceOfItems.h>

#include <algorithm>

#include "sources/readers/detail/text_header.h"

namespace voxlink::sources {

std::string stringValue(const gdcm::DataSet& ds, uint16_t group, uint16_t element) {
  const gdcm::Tag tag(group, element);
  if (!ds.FindDataElement(tag)) return {};
  const gdcm::ByteValue* bv = ds.GetDataElement(tag).GetByteValue();
  if (!bv) return {};
  std::string s(bv->GetPointer(), bv->GetLength());
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return std::string(trim(s));
}

Result<std::vector<double>> decimals(const gdcm::DataSet& ds, uint16_t group, uint16_t element,
                                     const std::string& file, const char* name, size_t count) {
  std::string text = stringValue(ds, group, element);
  if (text.empty()) return makeError(ErrorCode::kUnsupported, file, ": tag ", name, " missing");
  std::replace(text.begin(), text.end(), '\\', ' ');
  if (count == 0) return parseDoubles(text, file, name);
  return parseDoubles(text, file, name, count);
}

Result<std::optional<std::vector<double>>> optionalDecimals(const gdcm::DataSet& ds, uint16_t group,
                                                            uint16_t element,
                                                            const std::string& file,
                                                            const char* name, size_t count) {
  if (stringValue(ds, group, element).empty()) return std::optional<std::vector<double>>{};
  VOXLINK_ASSIGN_OR_RETURN(std::vector<double> v, decimals(ds, group, element, file, name, count));
  return std::optional<std::vector<double>>(std::move(v));
}

std::vector<gdcm::DataSet> sequenceItems(const gdcm::DataSet& ds, uint16_t group,
                                         uint16_t element) {
  std::vector<gdcm::DataSet> items;
  const gdcm::Tag tag(group, element);
  if (!ds.FindDataElement(tag)) return items;
  const gdcm::SmartPointer<gdcm::SequenceOfItems> sq = ds.GetDataElement(tag).GetValueAsSQ();
  if (!sq) return items;
  for (gdcm::SequenceOfItems::SizeType i = 1; i <= sq->GetNumberOfItems(); ++i)
    items.push_back(sq->GetItem(i).GetNestedDataSet());
  return items;
}

std::optional<gdcm::DataSet> functionalGroup(const gdcm::DataSet* perFrame,
                                             const gdcm::DataSet* shared, uint16_t group,
                                             uint16_t element) {
  for (const gdcm::DataSet* g : {perFrame, shared}) {
    if (!g) continue;
    auto items = sequenceItems(*g, group, element);
    if (!items.empty()) return std::move(items.front());
  }
  return std::nullopt;
}

}  // namespace voxlink::sources
