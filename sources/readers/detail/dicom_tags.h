// SPDX-License-Identifier: BSD-3-Clause
// Reading single DICOM elements and functional-group items from a GDCM data set, with errors
// that name the file and the tag.
#pragma once

#include <gdcmAttribute.h>
#include <gdcmDataSet.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::sources {

// The text of a string-valued element (DS, IS, UI, CS, LO), trailing padding removed; empty
// when absent.
std::string stringValue(const gdcm::DataSet& ds, uint16_t group, uint16_t element);

// Backslash-separated decimal values ("0.5\0.5"). `count` 0: any number, at least one.
// kUnsupported when the element is absent; kCorrupt when malformed. `name` is "Tag (gggg,eeee)".
Result<std::vector<double>> decimals(const gdcm::DataSet& ds, uint16_t group, uint16_t element,
                                     const std::string& file, const char* name, size_t count);

// The same, or nullopt when the element is absent or empty.
Result<std::optional<std::vector<double>>> optionalDecimals(const gdcm::DataSet& ds, uint16_t group,
                                                            uint16_t element,
                                                            const std::string& file,
                                                            const char* name, size_t count);

template <uint16_t G, uint16_t E>
std::optional<uint16_t> ushortValue(const gdcm::DataSet& ds) {
  gdcm::Attribute<G, E> at;
  if (!ds.FindDataElement(at.GetTag()) || ds.GetDataElement(at.GetTag()).IsEmpty())
    return std::nullopt;
  at.SetFromDataSet(ds);
  return static_cast<uint16_t>(at.GetValue());
}

// Copies of the items' data sets of a sequence element; empty when absent or not a sequence
// (copies: GDCM may build the sequence afresh from an implicit-VR value on each call).
std::vector<gdcm::DataSet> sequenceItems(const gdcm::DataSet& ds, uint16_t group, uint16_t element);

// The first item of functional-group macro (group, element): from the frame's own group when it
// holds the macro, else from the shared group; nullopt when neither does.
std::optional<gdcm::DataSet> functionalGroup(const gdcm::DataSet* perFrame,
                                             const gdcm::DataSet* shared, uint16_t group,
                                             uint16_t element);

}  // namespace voxlink::sources
