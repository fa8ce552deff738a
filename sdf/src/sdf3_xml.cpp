#include "semo/sdf/sdf3_xml.hpp"

#include <map>
#include <set>

#include "semo/frontend/xml_reader.hpp"

namespace semo::sdf {

namespace {

using tinyxml2::XMLElement;

constexpr std::int64_t kMaxRate = 1'000'000'000;
constexpr std::int64_t kMaxTokens = 1'000'000'000'000;

struct Port {
  bool output = false;
  std::int64_t rate = 1;
  const XMLElement* element = nullptr;
  bool connected = false;
};

class Sdf3Reader {
 public:
  Sdf3Reader(const SourceManager& sources, FileId file, DiagnosticEngine& diags) : xml_(sources, file, diags), diags_(diags) {}

  std::optional<Graph> read() {
    tinyxml2::XMLDocument doc;
    if (!xml_.parse(doc)) return std::nullopt;
    const XMLElement* root = doc.RootElement();
    if (root == nullptr || std::string_view(root->Name()) != "sdf3") {
      if (root != nullptr) xml_.error(root, "not an SDF3 graph: the root element must be <sdf3>");
      else diags_.error({{xml_.file(), 1, 1}, 1}, "not an SDF3 graph: the document is empty");
      return std::nullopt;
    }
    if (const char* type = root->Attribute("type"); type != nullptr && std::string_view(type) != "sdf") {
      xml_.attributeError(root, "type", std::string("only SDF graphs (type=\"sdf\") are supported, not '") + type + "'");
      return std::nullopt;
    }
    const XMLElement* app = root->FirstChildElement("applicationGraph");
    const XMLElement* sdf = app != nullptr ? app->FirstChildElement("sdf") : nullptr;
    if (sdf == nullptr) {
      xml_.error(app != nullptr ? app : root, "an SDF3 graph needs <applicationGraph> with an <sdf> element");
      return std::nullopt;
    }
    Graph g;
    if (const char* name = sdf->Attribute("name")) g.name = name;
    else if (const char* appName = app->Attribute("name")) g.name = appName;
    const std::size_t errorsBefore = diags_.errorCount();
    for (const XMLElement* a = sdf->FirstChildElement("actor"); a != nullptr; a = a->NextSiblingElement("actor")) readActor(a, g);
    for (const XMLElement* c = sdf->FirstChildElement("channel"); c != nullptr; c = c->NextSiblingElement("channel")) readChannel(c, g);
    if (const XMLElement* props = app->FirstChildElement("sdfProperties")) readProperties(props, g);
    if (g.actors.empty() && diags_.errorCount() == errorsBefore) xml_.error(sdf, "the graph has no actors");
    if (diags_.errorCount() != errorsBefore) return std::nullopt;
    return g;
  }

 private:
  void readActor(const XMLElement* e, Graph& g) {
    std::optional<std::string> name = xml_.required(e, "name");
    if (!name) return;
    if (actorIds_.count(*name) != 0) {
      xml_.attributeError(e, "name", "actor '" + *name + "' is defined twice");
      return;
    }
    actorIds_[*name] = static_cast<ActorId>(g.actors.size());
    g.actors.push_back({*name, 0, xml_.at(e)});
    std::map<std::string, Port>& ports = ports_[*name];
    for (const XMLElement* p = e->FirstChildElement("port"); p != nullptr; p = p->NextSiblingElement("port")) {
      std::optional<std::string> portName = xml_.required(p, "name");
      std::optional<std::string> type = xml_.required(p, "type");
      if (!portName || !type) continue;
      if (*type != "in" && *type != "out") {
        xml_.attributeError(p, "type", "a port's type is 'in' or 'out', not '" + *type + "'");
        continue;
      }
      if (ports.count(*portName) != 0) {
        xml_.attributeError(p, "name", "actor '" + *name + "' has two ports named '" + *portName + "'");
        continue;
      }
      // A port with a bad rate is still recorded (rate 0), so that its channel is not reported again.
      std::optional<std::int64_t> rate = positive(p, "rate", kMaxRate);
      ports[*portName] = {*type == "out", rate.value_or(0), p, false};
    }
  }

  // A required integer attribute in [1, max]; rates of cyclo-static graphs ("1,2") get their own word.
  std::optional<std::int64_t> positive(const XMLElement* e, const char* attribute, std::int64_t max) {
    const char* v = e->Attribute(attribute);
    if (v == nullptr) {
      xml_.error(e, std::string("<") + e->Name() + "> needs attribute '" + attribute + "'");
      return std::nullopt;
    }
    if (std::string_view(v).find(',') != std::string_view::npos) {
      xml_.attributeError(e, attribute, std::string("cyclo-static rates ('") + v + "') are not supported: SDF rates are single integers");
      return std::nullopt;
    }
    return xml_.integer(e, attribute, 1, max);
  }

  // The port `port` of actor `actor`, which must exist, have the given direction and be unused.
  std::optional<std::pair<ActorId, std::int64_t>> endpoint(const XMLElement* e, const char* actorAttr, const char* portAttr, bool output) {
    std::optional<std::string> actor = xml_.required(e, actorAttr);
    std::optional<std::string> port = xml_.required(e, portAttr);
    if (!actor || !port) return std::nullopt;
    auto a = actorIds_.find(*actor);
    if (a == actorIds_.end()) {
      xml_.attributeError(e, actorAttr, "no actor named '" + *actor + "'");
      return std::nullopt;
    }
    std::map<std::string, Port>& ports = ports_[*actor];
    auto p = ports.find(*port);
    if (p == ports.end()) {
      xml_.attributeError(e, portAttr, "actor '" + *actor + "' has no port named '" + *port + "'");
      return std::nullopt;
    }
    if (p->second.output != output) {
      xml_.attributeError(e, portAttr, "port '" + *port + "' of actor '" + *actor + "' is an " + (output ? "input" : "output") +
                                           " port; a channel " + (output ? "starts at an output" : "ends at an input"));
      return std::nullopt;
    }
    if (p->second.connected) {
      xml_.attributeError(e, portAttr, "port '" + *port + "' of actor '" + *actor + "' is connected to two channels");
      return std::nullopt;
    }
    p->second.connected = true;
    if (p->second.rate == 0) return std::nullopt;  // its error is reported already
    return std::pair{a->second, p->second.rate};
  }

  void readChannel(const XMLElement* e, Graph& g) {
    std::optional<std::string> name = xml_.required(e, "name");
    if (!name) return;
    if (!channelNames_.insert(*name).second) {
      xml_.attributeError(e, "name", "channel '" + *name + "' is defined twice");
      return;
    }
    auto source = endpoint(e, "srcActor", "srcPort", true);
    auto target = endpoint(e, "dstActor", "dstPort", false);
    std::int64_t initial = 0;
    if (e->Attribute("initialTokens") != nullptr) {
      std::optional<std::int64_t> t = xml_.integer(e, "initialTokens", 0, kMaxTokens);
      if (!t) return;
      initial = *t;
    }
    if (!source || !target) return;
    g.channels.push_back({*name, source->first, target->first, source->second, target->second, initial, xml_.at(e)});
  }

  // Execution times: per actor, the default processor's (else the first one's) <executionTime time>.
  void readProperties(const XMLElement* props, Graph& g) {
    for (const XMLElement* ap = props->FirstChildElement("actorProperties"); ap != nullptr; ap = ap->NextSiblingElement("actorProperties")) {
      std::optional<std::string> actor = xml_.required(ap, "actor");
      if (!actor) continue;
      auto id = actorIds_.find(*actor);
      if (id == actorIds_.end()) {
        xml_.attributeError(ap, "actor", "no actor named '" + *actor + "'");
        continue;
      }
      const XMLElement* chosen = nullptr;
      for (const XMLElement* p = ap->FirstChildElement("processor"); p != nullptr; p = p->NextSiblingElement("processor")) {
        if (chosen == nullptr || (p->Attribute("default") != nullptr && std::string_view(p->Attribute("default")) == "true")) chosen = p;
      }
      const XMLElement* time = chosen != nullptr ? chosen->FirstChildElement("executionTime") : nullptr;
      if (time == nullptr) {
        xml_.error(ap, "actor '" + *actor + "' has properties but no <processor><executionTime time=...>");
        continue;
      }
      if (time->Attribute("time") == nullptr) {
        xml_.error(time, "<executionTime> needs attribute 'time'");
        continue;
      }
      if (std::optional<std::int64_t> t = xml_.integer(time, "time", 0, kMaxTokens)) {
        g.actors[id->second].executionTime = *t;
      }
    }
  }

  xml::Reader xml_;
  DiagnosticEngine& diags_;
  std::map<std::string, ActorId> actorIds_;
  std::map<std::string, std::map<std::string, Port>> ports_;
  std::set<std::string> channelNames_;
};

}  // namespace

std::optional<Graph> readSdf3(const SourceManager& sources, FileId file, DiagnosticEngine& diags) {
  return Sdf3Reader(sources, file, diags).read();
}

}  // namespace semo::sdf

namespace semo::sdf {

namespace {

// Text for an XML attribute value.
std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Text for a Graphviz quoted string.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string writeSdf3(const Graph& g) {
  // Ports are named after the channel and its end: unique per actor, whatever the channels' names.
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<sdf3 type=\"sdf\" version=\"1.0\">\n";
  out += "  <applicationGraph name=\"" + escaped(g.name) + "\">\n    <sdf name=\"" + escaped(g.name) + "\" type=\"" + escaped(g.name) + "\">\n";
  // Each actor's ports in the order of their channels, found in one pass over the channels (not one
  // per actor: a graph of n actors and n channels would cost n^2).
  std::vector<std::string> ports(g.actors.size());
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    const Channel& ch = g.channels[c];
    if (ch.source < ports.size()) ports[ch.source] += "        <port name=\"out" + std::to_string(c) + "\" type=\"out\" rate=\"" + std::to_string(ch.production) + "\"/>\n";
    if (ch.target < ports.size()) ports[ch.target] += "        <port name=\"in" + std::to_string(c) + "\" type=\"in\" rate=\"" + std::to_string(ch.consumption) + "\"/>\n";
  }
  for (ActorId a = 0; a < g.actors.size(); ++a) {
    out += "      <actor name=\"" + escaped(g.actors[a].name) + "\" type=\"" + escaped(g.actors[a].name) + "\">\n";
    out += ports[a];
    out += "      </actor>\n";
  }
  for (std::size_t c = 0; c < g.channels.size(); ++c) {
    const Channel& ch = g.channels[c];
    out += "      <channel name=\"" + escaped(ch.name) + "\" srcActor=\"" + escaped(g.actors[ch.source].name) + "\" srcPort=\"out" +
           std::to_string(c) + "\" dstActor=\"" + escaped(g.actors[ch.target].name) + "\" dstPort=\"in" + std::to_string(c) + "\"";
    if (ch.initialTokens != 0) out += " initialTokens=\"" + std::to_string(ch.initialTokens) + "\"";
    out += "/>\n";
  }
  out += "    </sdf>\n    <sdfProperties>\n";
  for (const Actor& a : g.actors) {
    out += "      <actorProperties actor=\"" + escaped(a.name) + "\">\n        <processor type=\"p1\" default=\"true\">\n";
    out += "          <executionTime time=\"" + std::to_string(a.executionTime) + "\"/>\n        </processor>\n      </actorProperties>\n";
  }
  out += "    </sdfProperties>\n  </applicationGraph>\n</sdf3>\n";
  return out;
}

std::string toGraphviz(const Graph& g) {
  std::string out = "digraph " + quoted(g.name) + " {\n  node [shape=box];\n";
  for (ActorId a = 0; a < g.actors.size(); ++a) {
    out += "  a" + std::to_string(a) + " [label=" + quoted(g.actors[a].name + " (" + std::to_string(g.actors[a].executionTime) + ")") + "];\n";
  }
  for (const Channel& ch : g.channels) {
    std::string label = ch.name + ": " + std::to_string(ch.production) + " -> " + std::to_string(ch.consumption);
    if (ch.initialTokens != 0) label += " (" + std::to_string(ch.initialTokens) + " tokens)";
    out += "  a" + std::to_string(ch.source) + " -> a" + std::to_string(ch.target) + " [label=" + quoted(label) + "];\n";
  }
  return out + "}\n";
}

}  // namespace semo::sdf
