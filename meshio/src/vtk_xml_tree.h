#pragma once
// The element tree of a VTK XML file (.vtp), read by ffdkit instead of VTK's parser, which
// trusts what a file announces (fuzz_mesh_vtp made it write past its own arrays). Only what VTK
// XML files use: elements, attributes, character data, comments, the XML declaration, and the
// <AppendedData> section whose bytes after its '_' are raw or base64 data, not XML. Private
// to meshio; vtk_xml_arrays.h decodes the DataArray elements, vtp_format.cpp builds the mesh.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ffdkit::meshio::detail {

struct XmlAttribute {
  std::string_view name;
  std::string_view value;  ///< as written between the quotes (entities are not expanded)
};

struct XmlElement {
  std::string_view name;
  std::vector<XmlAttribute> attributes;
  std::string_view text;  ///< the character data between the start tag and the first child or end tag
  std::vector<XmlElement> children;
  std::size_t offset = 0;  ///< of the '<' of its start tag in the file (for the line in messages)

  /// The first attribute of this name.
  std::optional<std::string_view> attribute(std::string_view attributeName) const;
  /// The first child element of this name, or nullptr.
  const XmlElement* child(std::string_view childName) const;
};

/// A parsed VTK XML file: the root element (VTKFile) and its appended data, if any.
struct VtkXmlDocument {
  std::string_view bytes;  ///< the whole file, for line numbers
  XmlElement root;
  std::string_view appended;    ///< the bytes after <AppendedData>'s '_' up to its end tag
  bool appendedBase64 = false;  ///< encoding="base64" (else raw)

  /// 1-based line of a byte offset.
  std::size_t lineOf(std::size_t offset) const;
  /// "source:line: " for an element.
  std::string where(const std::string& source, const XmlElement& element) const;
};

/// Parses `bytes`. @throws MeshIoError naming the file and the line: malformed tags, an end
/// tag that does not match, elements nested deeper than 32, DOCTYPE or CDATA sections, no
/// VTKFile root, an <AppendedData> without its '_' or its end tag.
VtkXmlDocument parseVtkXml(std::string_view bytes, const std::string& source);

}  // namespace ffdkit::meshio::detail
