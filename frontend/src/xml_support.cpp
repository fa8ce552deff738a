#include "semo/frontend/xml_reader.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace semo::xml {

namespace {

// tinyxml2 compares each attribute of an element with every one before it (to refuse one given
// twice): an element of n attributes costs n^2. No element of semo's inputs has more than a dozen.
constexpr std::size_t kMaxAttributes = 1000;

// The offset of the first start tag with more than kMaxAttributes attributes, if there is one: the
// '=' outside quoted values of each tag, counted before tinyxml2 reads the text. Comments, CDATA,
// declarations and processing instructions are skipped; anything malformed is tinyxml2's to report.
std::optional<std::size_t> tagWithTooManyAttributes(std::string_view t) {
  for (std::size_t i = t.find('<'); i != std::string_view::npos && i < t.size(); i = t.find('<', i + 1)) {
    auto skipTo = [&](std::string_view end) {
      const std::size_t at = t.find(end, i + 1);
      return at == std::string_view::npos ? t.size() : at + end.size() - 1;
    };
    if (t.substr(i, 4) == "<!--") {
      i = skipTo("-->");
    } else if (t.substr(i, 9) == "<![CDATA[") {
      i = skipTo("]]>");
    } else if (i + 1 < t.size() && (t[i + 1] == '?' || t[i + 1] == '!')) {
      i = skipTo(">");
    } else {
      std::size_t attributes = 0;
      char quote = 0;
      std::size_t j = i + 1;
      for (; j < t.size(); ++j) {
        const char c = t[j];
        if (quote != 0) {
          if (c == quote) quote = 0;
        } else if (c == '"' || c == '\'') {
          quote = c;
        } else if (c == '=') {
          if (++attributes > kMaxAttributes) return i;
        } else if (c == '>') {
          break;
        }
      }
      i = j;
    }
  }
  return std::nullopt;
}

}  // namespace

bool Reader::parse(tinyxml2::XMLDocument& doc) {
  const std::string& text = sources_.text(file_);
  // XML is UTF-8 text (tinyxml2 reads no other encoding, and checks none): names and values read
  // here are written out again, in JSON among others.
  if (const std::size_t bad = firstInvalidUtf8(text); bad != std::string_view::npos) {
    static const char* digits = "0123456789abcdef";
    const auto byte = static_cast<unsigned char>(text[bad]);
    diags_.error({sources_.locationAt(file_, bad), 1}, std::string("malformed XML: not UTF-8 text (byte 0x") + digits[byte >> 4] + digits[byte & 15] + ")");
    return false;
  }
  if (const auto tag = tagWithTooManyAttributes(text)) {
    std::uint32_t line = 1, column = 1;
    for (std::size_t i = 0; i < *tag; ++i) {
      if (text[i] == '\n') ++line, column = 1;
      else ++column;
    }
    std::size_t nameEnd = *tag + 1;
    while (nameEnd < text.size() && std::string_view(" \t\r\n/>").find(text[nameEnd]) == std::string_view::npos) ++nameEnd;
    const std::string name = text.substr(*tag + 1, std::min<std::size_t>(nameEnd - *tag - 1, 100));
    diags_.error({{file_, line, column}, static_cast<std::uint32_t>(name.size() + 1)},
                 "element <" + name + "> has more than " + std::to_string(kMaxAttributes) + " attributes");
    return false;
  }
  if (doc.Parse(text.data(), text.size()) == tinyxml2::XML_SUCCESS) {
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (root != nullptr && root->NextSiblingElement() != nullptr) {
      error(root->NextSiblingElement(), "malformed XML: a second root element (a document has exactly one)");
      return false;
    }
    return true;
  }
  auto line = static_cast<std::uint32_t>(std::max(doc.ErrorLineNum(), 1));
  // tinyxml2's own text ("Error=XML_ERROR_MISMATCHED_ELEMENT ErrorID=14 (0xe) Line number=2:
  // XMLElement name=service") names the culprit; say it in words a user reads.
  std::string raw = doc.ErrorStr() ? doc.ErrorStr() : "";
  std::string element;
  if (auto at = raw.find("name="); at != std::string::npos) element = raw.substr(at + 5);
  std::string message;
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      message = "element <" + element + "> is not closed, or is closed by the wrong tag";
      break;
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: message = "malformed element" + (element.empty() ? "" : " <" + element + ">"); break;
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      message = "malformed attribute (a value not in quotes, or an attribute given twice)";
      break;
    case tinyxml2::XML_ERROR_PARSING_TEXT: message = "malformed text (a '<' or '&' must be escaped)"; break;
    case tinyxml2::XML_ERROR_PARSING_COMMENT: message = "unterminated comment"; break;
    case tinyxml2::XML_ERROR_PARSING_CDATA: message = "unterminated CDATA section"; break;
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: message = "malformed XML declaration"; break;
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: message = "the document is empty"; break;
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED: message = "elements are nested too deeply"; break;
    default: message = "cannot parse the document"; break;
  }
  std::uint32_t column = 1;
  std::uint32_t length = 1;
  if (!element.empty()) {
    std::string_view lineText = sources_.lineText(file_, line);
    if (auto pos = lineText.find("<" + element); pos != std::string_view::npos) {
      column = static_cast<std::uint32_t>(pos + 1);
      length = static_cast<std::uint32_t>(element.size() + 1);
    }
  }
  diags_.error({{file_, line, column}, length}, "malformed XML: " + message);
  return false;
}

SourceRange Reader::at(const tinyxml2::XMLElement* e) const {
  auto line = static_cast<std::uint32_t>(std::max(e->GetLineNum(), 1));
  std::string open = std::string("<") + e->Name();
  // Remembered: on a line of thousands of elements, searching it again for each would cost n^2.
  auto [known, added] = columns_.try_emplace({line, open}, 0);
  if (added) {
    std::string_view text = sources_.lineText(file_, line);
    const std::size_t col = text.find(open);
    known->second = col == std::string_view::npos ? 0 : static_cast<std::uint32_t>(col + 1);
  }
  if (known->second == 0) return {{file_, line, 1}, 1};
  return {{file_, line, known->second}, static_cast<std::uint32_t>(open.size())};
}

SourceRange Reader::attributeAt(const tinyxml2::XMLElement* e, std::string_view attribute, bool atValue) const {
  SourceRange element = at(e);
  std::uint32_t last = std::min(sources_.lineCount(file_), element.begin.line + 20);
  for (std::uint32_t line = element.begin.line; line <= last; ++line) {
    std::string_view text = sources_.lineText(file_, line);
    std::size_t from = line == element.begin.line ? element.begin.column : 0;
    for (std::size_t pos = text.find(attribute, from); pos != std::string_view::npos;
         pos = text.find(attribute, pos + 1)) {
      bool boundary = pos == 0 || text[pos - 1] == ' ' || text[pos - 1] == '\t';
      std::size_t after = pos + attribute.size();
      while (after < text.size() && text[after] == ' ') ++after;
      if (!boundary || after >= text.size() || text[after] != '=') continue;
      if (!atValue) {
        return {{file_, line, static_cast<std::uint32_t>(pos + 1)}, static_cast<std::uint32_t>(attribute.size())};
      }
      std::size_t quote = after + 1;
      while (quote < text.size() && text[quote] == ' ') ++quote;
      if (quote < text.size() && (text[quote] == '"' || text[quote] == '\'')) {
        std::size_t end = text.find(text[quote], quote + 1);
        std::size_t length = end == std::string_view::npos ? 1 : end - quote + 1;
        return {{file_, line, static_cast<std::uint32_t>(quote + 1)}, static_cast<std::uint32_t>(length)};
      }
      return {{file_, line, static_cast<std::uint32_t>(pos + 1)}, static_cast<std::uint32_t>(attribute.size())};
    }
    if (text.find('>') != std::string_view::npos && line > element.begin.line) break;
  }
  return element;
}

void Reader::checkAttributes(const tinyxml2::XMLElement* e, std::initializer_list<std::string_view> allowed) {
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
    bool known = false;
    for (std::string_view name : allowed) known = known || name == a->Name();
    if (known) continue;
    std::string list;
    for (std::string_view name : allowed) list += (list.empty() ? "" : ", ") + std::string(name);
    diags_.error(attributeAt(e, a->Name(), false), std::string("unknown attribute '") + a->Name() + "' of <" + e->Name() +
                                                "> (allowed: " + (list.empty() ? "none" : list) + ")");
  }
}

void Reader::checkChildren(const tinyxml2::XMLElement* e, std::initializer_list<std::string_view> allowed) {
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
    bool known = false;
    for (std::string_view name : allowed) known = known || name == c->Name();
    if (known) continue;
    std::string list;
    for (std::string_view name : allowed) list += (list.empty() ? "" : ", ") + ("<" + std::string(name) + ">");
    error(c, std::string("unknown element <") + c->Name() + "> inside <" + e->Name() +
                 "> (allowed: " + (list.empty() ? "none" : list) + ")");
  }
}

std::optional<std::string> Reader::required(const tinyxml2::XMLElement* e, const char* attribute) {
  const char* v = e->Attribute(attribute);
  if (v == nullptr) {
    error(e, std::string("<") + e->Name() + "> needs attribute '" + attribute + "'");
    return std::nullopt;
  }
  if (*v == '\0') {
    attributeError(e, attribute, std::string("attribute '") + attribute + "' of <" + e->Name() + "> is empty");
    return std::nullopt;
  }
  return std::string(v);
}

std::optional<std::int64_t> Reader::integer(const tinyxml2::XMLElement* e, const char* attribute, std::int64_t min,
                                            std::int64_t max) {
  const char* v = e->Attribute(attribute);
  if (v == nullptr) return std::nullopt;
  std::string_view text(v);
  std::int64_t n = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || ptr != text.data() + text.size()) {
    attributeError(e, attribute, std::string("attribute '") + attribute + "' must be an integer, not '" + v + "'");
    return std::nullopt;
  }
  if (n < min || n > max) {
    attributeError(e, attribute, std::string("attribute '") + attribute + "' must be between " + std::to_string(min) +
                                     " and " + std::to_string(max) + ", not " + std::to_string(n));
    return std::nullopt;
  }
  return n;
}

std::optional<double> Reader::number(const tinyxml2::XMLElement* e, const char* attribute) {
  const char* v = e->Attribute(attribute);
  if (v == nullptr) return std::nullopt;
  char* end = nullptr;
  double d = std::strtod(v, &end);
  if (end == v || *end != '\0' || !std::isfinite(d)) {
    attributeError(e, attribute, std::string("attribute '") + attribute + "' must be a number, not '" + v + "'");
    return std::nullopt;
  }
  return d;
}

std::optional<std::int64_t> Reader::durationMicros(const tinyxml2::XMLElement* e, const char* attribute) {
  const char* v = e->Attribute(attribute);
  if (v == nullptr) return std::nullopt;
  std::string_view text(v);
  std::int64_t amount = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), amount);
  std::string_view unit = text.substr(static_cast<std::size_t>(ptr - text.data()));
  while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
  std::int64_t scale = 0;
  if (unit == "USEC" || unit == "us") scale = 1;
  if (unit == "MSEC" || unit == "ms") scale = 1000;
  if (unit == "SEC" || unit == "s") scale = 1000000;
  if (unit == "MIN" || unit == "min") scale = 60000000;
  if (ec != std::errc() || scale == 0 || amount < 0 || amount > 1000000000) {
    attributeError(e, attribute, std::string("attribute '") + attribute + "' must be a duration such as '500 MSEC' or '2 SEC', not '" +
                                     v + "'");
    return std::nullopt;
  }
  return amount * scale;
}

std::vector<std::string> splitList(std::string_view text) {
  std::vector<std::string> out;
  std::string current;
  for (char c : text) {
    if (c == ' ' || c == ',' || c == '\t' || c == '\n' || c == '\r') {
      if (!current.empty()) out.push_back(std::move(current));
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) out.push_back(std::move(current));
  return out;
}

}  // namespace semo::xml
