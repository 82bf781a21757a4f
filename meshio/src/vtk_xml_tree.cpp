#include "vtk_xml_tree.h"

#include <algorithm>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio::detail {
namespace {

constexpr std::size_t kMaxDepth = 32;  // VTK's PolyData files nest 6 deep (VTKFile/PolyData/Piece/Points/DataArray/InformationKey/Value)

// Joins pieces of a message (appends, which GCC 12's -Wrestrict does not misread as
// operator+ chains of std::string temporaries can be).
template <class... Pieces>
std::string concat(const Pieces&... pieces) {
  std::string text;
  (text.append(std::string_view(pieces)), ...);
  return text;
}

// XML white space (the XML 1.0 S production).
bool isXmlSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool isNameChar(char c) { return !isXmlSpace(c) && c != '/' && c != '>' && c != '=' && c != '<' && c != '"' && c != '\''; }

class Parser {
 public:
  Parser(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) { document_.bytes = bytes; }

  VtkXmlDocument parse() {
    std::vector<XmlElement> open;  // the elements whose end tag is still to come, outermost first
    bool rootDone = false;
    while (true) {
      const std::size_t lt = bytes_.find('<', pos_);
      if (!open.empty() && open.back().children.empty() && open.back().text.data() == nullptr)
        open.back().text = bytes_.substr(pos_, (lt == std::string_view::npos ? bytes_.size() : lt) - pos_);
      if (lt == std::string_view::npos) break;
      pos_ = lt;
      if (startsWith("<?")) {
        skipPast("?>", "processing instruction");
      } else if (startsWith("<!--")) {
        skipPast("-->", "comment");
      } else if (startsWith("<!")) {
        fail(lt, "DOCTYPE and CDATA sections are not part of VTK's XML files");
      } else if (startsWith("</")) {
        const std::size_t at = pos_;
        pos_ += 2;
        const std::string_view name = readName();
        skipSpaces();
        if (pos_ >= bytes_.size() || bytes_[pos_] != '>') fail(at, concat("the end tag </", name, " is not closed"));
        ++pos_;
        if (open.empty() || open.back().name != name)
          fail(at, concat("</", name, "> does not close ", open.empty() ? std::string_view("any element") : std::string_view("<"),
                          open.empty() ? std::string_view() : open.back().name, open.empty() ? "" : ">"));
        closeElement(open, rootDone);
      } else {
        if (rootDone) fail(lt, "content after the root element");
        bool selfClosing = false;
        XmlElement element = readStartTag(selfClosing);
        if (open.size() >= kMaxDepth) fail(lt, "elements nest deeper than " + std::to_string(kMaxDepth));
        const bool appended = element.name == "AppendedData";
        open.push_back(std::move(element));
        if (selfClosing) {
          closeElement(open, rootDone);
        } else if (appended) {
          readAppendedData(open.back());
        }
      }
    }
    if (!open.empty()) fail(open.back().offset, concat("<", open.back().name, "> is not closed"));
    if (!rootDone) fail(0, "no VTKFile element");
    return std::move(document_);
  }

 private:
  bool startsWith(std::string_view prefix) const { return bytes_.substr(pos_, prefix.size()) == prefix; }

  void skipSpaces() {
    while (pos_ < bytes_.size() && isXmlSpace(bytes_[pos_])) ++pos_;
  }

  void skipPast(std::string_view end, const char* what) {
    const std::size_t at = bytes_.find(end, pos_);
    if (at == std::string_view::npos) fail(pos_, std::string("the ") + what + " is not closed");
    pos_ = at + end.size();
  }

  std::string_view readName() {
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && isNameChar(bytes_[pos_])) ++pos_;
    if (pos_ == start) fail(start, "expected a name");
    return bytes_.substr(start, pos_ - start);
  }

  // From '<' to just past '>' (or "/>").
  XmlElement readStartTag(bool& selfClosing) {
    XmlElement element;
    element.offset = pos_;
    ++pos_;
    element.name = readName();
    while (true) {
      skipSpaces();
      if (pos_ >= bytes_.size()) fail(element.offset, concat("the tag <", element.name, " is not closed"));
      if (bytes_[pos_] == '>') {
        ++pos_;
        return element;
      }
      if (startsWith("/>")) {
        pos_ += 2;
        selfClosing = true;
        return element;
      }
      XmlAttribute attribute;
      attribute.name = readName();
      skipSpaces();
      if (pos_ >= bytes_.size() || bytes_[pos_] != '=')
        failAttribute(element, attribute.name, " has no value");
      ++pos_;
      skipSpaces();
      if (pos_ >= bytes_.size() || (bytes_[pos_] != '"' && bytes_[pos_] != '\''))
        failAttribute(element, attribute.name, "'s value is not quoted");
      const std::size_t end = bytes_.find(bytes_[pos_], pos_ + 1);
      if (end == std::string_view::npos)
        failAttribute(element, attribute.name, "'s value is not closed");
      attribute.value = bytes_.substr(pos_ + 1, end - pos_ - 1);
      pos_ = end + 1;
      element.attributes.push_back(attribute);
    }
  }

  // After <AppendedData ...>: blanks, '_', then data that is not XML up to the LAST
  // </AppendedData> of the file (raw bytes may contain anything, '<' included).
  void readAppendedData(XmlElement& element) {
    if (sawAppended_) fail(element.offset, "a second <AppendedData>");
    sawAppended_ = true;
    skipSpaces();
    if (pos_ >= bytes_.size() || bytes_[pos_] != '_') fail(element.offset, "<AppendedData>: its data do not start with '_'");
    const std::size_t start = pos_ + 1;
    const std::size_t end = bytes_.rfind("</AppendedData");
    if (end == std::string_view::npos || end < start) fail(element.offset, "<AppendedData> is not closed");
    document_.appended = bytes_.substr(start, end - start);
    document_.appendedBase64 = element.attribute("encoding") == std::string_view("base64");
    if (const auto encoding = element.attribute("encoding"); encoding && *encoding != "raw" && *encoding != "base64")
      fail(element.offset, concat("<AppendedData>: unknown encoding \"", *encoding, "\" (raw or base64)"));
    element.text = {};
    pos_ = end;  // the end tag is read as any other
  }

  void closeElement(std::vector<XmlElement>& open, bool& rootDone) {
    XmlElement element = std::move(open.back());
    open.pop_back();
    if (open.empty()) {
      if (element.name != "VTKFile") fail(element.offset, concat("the root element is <", element.name, ">, not <VTKFile>"));
      document_.root = std::move(element);
      rootDone = true;
    } else {
      open.back().children.push_back(std::move(element));
    }
  }

  [[noreturn]] void failAttribute(const XmlElement& element, std::string_view attribute, const char* what) const {
    fail(element.offset, concat("<", element.name, ">: attribute ", attribute, what));
  }

  [[noreturn]] void fail(std::size_t offset, const std::string& message) const {
    throw MeshIoError(source_ + ":" + std::to_string(document_.lineOf(offset)) + ": " + message);
  }

  std::string_view bytes_;
  const std::string& source_;
  std::size_t pos_ = 0;
  bool sawAppended_ = false;
  VtkXmlDocument document_;
};

}  // namespace

std::optional<std::string_view> XmlElement::attribute(std::string_view attributeName) const {
  for (const XmlAttribute& a : attributes)
    if (a.name == attributeName) return a.value;
  return std::nullopt;
}

const XmlElement* XmlElement::child(std::string_view childName) const {
  for (const XmlElement& c : children)
    if (c.name == childName) return &c;
  return nullptr;
}

std::size_t VtkXmlDocument::lineOf(std::size_t offset) const {
  offset = std::min(offset, bytes.size());
  return 1 + std::size_t(std::count(bytes.begin(), bytes.begin() + std::ptrdiff_t(offset), '\n'));
}

std::string VtkXmlDocument::where(const std::string& source, const XmlElement& element) const {
  return source + ":" + std::to_string(lineOf(element.offset)) + ": ";
}

VtkXmlDocument parseVtkXml(std::string_view bytes, const std::string& source) { return Parser(bytes, source).parse(); }

}  // namespace ffdkit::meshio::detail
