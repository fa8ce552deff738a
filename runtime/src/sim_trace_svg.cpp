// The picture of a simulated run (sim_trace.hpp, renderSvg): on top the world seen from above (y up)
// with each robot's trajectory, below it a timeline per robot, then a legend. Plain SVG 1.1 with
// presentation attributes only (no CSS, no scripts, no external references), so that any viewer and
// rsvg-convert draw the same thing. Every drawn item carries a class ("trajectory", "mode-band",
// "crash", ...) so that tests and scripts can find them; coordinates have two decimals, so the same
// trace always gives the same bytes.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "semo/runtime/sim_trace.hpp"
#include "text_output.hpp"

namespace semo::runtime {

namespace {

using detail::fixed;

constexpr double kWidth = 960;
constexpr double kMargin = 20;
constexpr double kWorldMaxHeight = 460;
constexpr double kLabelColumn = 120;  // robot names left of the timeline
constexpr double kRowHeight = 44;   // a robot's row with one lane of roles
constexpr double kLaneHeight = 12;  // each further group block it holds a role in
// Robots: strong colours, none of them red (red means a crash, a lost message or a violation).
constexpr const char* kRobotColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b",
                                         "#e377c2", "#17becf", "#bcbd22", "#393b79", "#637939"};
// Modes: light colours, so that the black mode names stay readable on them.
constexpr const char* kModeColours[] = {"#aec7e8", "#ffbb78", "#98df8a", "#c5b0d5", "#f7b6d2",
                                        "#9edae5", "#dbdb8d", "#c49c94", "#e5e5e5", "#fdd0a2"};

std::string n2(double x) { return fixed(x, 2); }

std::string xml(std::string_view raw) {
  std::string out;
  for (char c : detail::validUtf8(raw)) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;  // XML 1.0 forbids most control characters
    }
  }
  return out;
}

// About how wide a text is drawn in a sans-serif font (to decide whether a name fits in a band).
double textWidth(std::string_view s, double fontSize) { return static_cast<double>(s.size()) * fontSize * 0.65; }

// A step of 1, 2 or 5 times a power of ten giving at most `count` intervals over `span`.
double niceStep(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10 * power;
}

std::string tickLabel(double x, double step) { return fixed(x, step >= 1 ? 0 : step >= 0.1 ? 1 : 2); }

class Picture {
 public:
  explicit Picture(const SimTrace& trace) : tr_(trace), lanes_(trace.robots.size()) {
    std::vector<std::string> blocks;  // every block with a role, in the order of its first role event
    for (const TraceEvent& e : tr_.events) {
      if (e.kind == TraceEvent::Kind::Role && std::find(blocks.begin(), blocks.end(), e.block) == blocks.end()) blocks.push_back(e.block);
    }
    for (const TraceEvent& e : tr_.events) {
      if (e.kind == TraceEvent::Kind::Mode) modeColour(e.detail);
      if (e.kind == TraceEvent::Kind::Role && e.robot < lanes_.size()) {
        std::vector<std::string>& mine = lanes_[e.robot];
        if (std::find(mine.begin(), mine.end(), e.block) == mine.end()) mine.push_back(e.block);
      }
      end_ = std::max(end_, e.t);
    }
    // Each robot's lanes in the same order, so that a block's lane is at the same height on every row.
    auto order = [&](const std::string& b) { return std::find(blocks.begin(), blocks.end(), b) - blocks.begin(); };
    for (std::vector<std::string>& mine : lanes_) {
      std::sort(mine.begin(), mine.end(), [&](const std::string& a, const std::string& b) { return order(a) < order(b); });
    }
    for (const PoseSample& s : tr_.poses) end_ = std::max(end_, s.t);
    if (tr_.duration > 0) end_ = tr_.duration;
    if (!(end_ > 0) || !std::isfinite(end_)) end_ = 1;
  }

  std::string render() {
    double y = kMargin;
    // The title, and the faults on a line of their own when both do not fit on one.
    const std::string whole = title(true);
    if (textWidth(whole, 14) <= kWidth - 2 * kMargin) {
      text(kMargin, y + 4, 14, xml(whole), "title", "font-weight=\"bold\"");
    } else {
      text(kMargin, y + 4, 14, xml(title(false)), "title", "font-weight=\"bold\"");
      y += 16;
      text(kMargin, y + 4, 11, xml("faults: " + tr_.faults), "title-faults");
    }
    y += 16;
    y = world(y) + 36;
    y = timeline(y) + 24;
    y = legend(y);
    const std::string height = n2(y + kMargin);
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + n2(kWidth) + "\" height=\"" + height +
           "\" viewBox=\"0 0 " + n2(kWidth) + " " + height + "\" font-family=\"sans-serif\">\n"
           "<rect class=\"background\" x=\"0\" y=\"0\" width=\"" + n2(kWidth) + "\" height=\"" + height + "\" fill=\"#ffffff\"/>\n" +
           out_ + "</svg>\n";
  }

 private:
  const SimTrace& tr_;
  // Per robot: the group blocks it holds roles in, a lane each, in the order the run first saw a
  // role in them ("": a role event that names no block).
  std::vector<std::vector<std::string>> lanes_;
  std::string out_;
  double end_ = 0;  // the timeline's last second
  std::map<std::string, std::size_t> modes_;  // mode -> colour, in order of first appearance
  // World -> picture: x' = left + (x - minX)·scale, y' = top + (maxY - y)·scale (y points up).
  double minX_ = 0, maxY_ = 0, scale_ = 1, left_ = 0, top_ = 0;
  // What is drawn in the world so far that a label must not cover: marks, then labels.
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> taken_;

  std::string px(Vec2 p) const { return n2(left_ + (p.x - minX_) * scale_) + "," + n2(top_ + (maxY_ - p.y) * scale_); }
  double sx(double x) const { return left_ + (x - minX_) * scale_; }
  double sy(double y) const { return top_ + (maxY_ - y) * scale_; }

  const char* modeColour(const std::string& mode) {
    auto it = modes_.try_emplace(mode, modes_.size()).first;
    return kModeColours[it->second % std::size(kModeColours)];
  }
  static const char* robotColour(std::size_t r) { return kRobotColours[r % std::size(kRobotColours)]; }

  std::string title(bool withFaults) const {
    std::string t = tr_.mission.empty() ? "simulated run" : tr_.mission;
    t += "  (seed " + std::to_string(tr_.seed) + ", " + fixed(tr_.duration, 1) + " s";
    if (withFaults && !tr_.faults.empty()) t += ", " + tr_.faults;
    return t + ")";
  }

  void text(double x, double y, double size, const std::string& escaped, const char* cls, const std::string& extra = "") {
    out_ += "<text class=\"" + std::string(cls) + "\" x=\"" + n2(x) + "\" y=\"" + n2(y) + "\" font-size=\"" + n2(size) + "\"" +
            (extra.empty() ? "" : " " + extra) + ">" + escaped + "</text>\n";
  }

  // The final pose of robot r: its last sample, else its start in the world.
  std::optional<Pose> lastPose(std::size_t r) const {
    for (auto it = tr_.poses.rbegin(); it != tr_.poses.rend(); ++it) {
      if (r < it->poses.size()) return it->poses[r];
    }
    if (const StartPose* s = tr_.world.start(tr_.robots[r].name)) return Pose{s->at.x, s->at.y, s->heading};
    return std::nullopt;
  }

  std::optional<double> crashTime(std::size_t r) const {
    for (const TraceEvent& e : tr_.events) {
      if (e.kind == TraceEvent::Kind::Crash && e.robot == r) return e.t;
    }
    return std::nullopt;
  }

  // The world's extent: the arena when the world has one, widened to whatever lies outside it.
  void bounds(double& x0, double& y0, double& x1, double& y1) const {
    x0 = y0 = INFINITY;
    x1 = y1 = -INFINITY;
    auto add = [&](Vec2 p, double r = 0) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
      x0 = std::min(x0, p.x - r), y0 = std::min(y0, p.y - r), x1 = std::max(x1, p.x + r), y1 = std::max(y1, p.y + r);
    };
    const World& w = tr_.world;
    if (w.arena) add(w.arena->first), add(w.arena->second);
    for (const Place& p : w.places) add(p.at);
    for (const StartPose& s : w.starts) add(s.at);
    for (const FactSite& f : w.facts) add(f.at, f.radius);
    for (const Obstacle& o : w.obstacles) {
      if (o.shape.kind == Shape::Kind::Circle) add(o.shape.center, o.shape.radius);
      for (const Vec2& p : o.shape.points) add(p);
    }
    for (const PoseSample& s : tr_.poses) {
      for (const Pose& p : s.poses) add({p.x, p.y});
    }
    if (!(x0 <= x1)) x0 = y0 = 0, x1 = y1 = 1;
    // A margin around what is drawn (none around an arena that already holds everything).
    const double pad = w.arena ? 0.0 : std::max(0.2, 0.04 * std::max(x1 - x0, y1 - y0));
    x0 -= pad, y0 -= pad, x1 += pad, y1 += pad;
    if (x1 - x0 < 1e-9) x0 -= 0.5, x1 += 0.5;
    if (y1 - y0 < 1e-9) y0 -= 0.5, y1 += 0.5;
  }

  double world(double top) {
    double x0, y0, x1, y1;
    bounds(x0, y0, x1, y1);
    const double room = kWidth - 2 * kMargin;
    scale_ = std::min(room / (x1 - x0), kWorldMaxHeight / (y1 - y0));
    minX_ = x0, maxY_ = y1, top_ = top;
    left_ = kMargin + (room - (x1 - x0) * scale_) / 2;
    const double w = (x1 - x0) * scale_, h = (y1 - y0) * scale_;
    out_ += "<g class=\"world\">\n";
    out_ += "<rect class=\"floor\" x=\"" + n2(left_) + "\" y=\"" + n2(top_) + "\" width=\"" + n2(w) + "\" height=\"" + n2(h) +
            "\" fill=\"#fbfbf8\" stroke=\"#999999\" stroke-width=\"0.8\"/>\n";
    // A metre grid (or coarser), labelled along the bottom and left edges.
    const double step = niceStep(std::max(x1 - x0, y1 - y0), 12);
    for (double gx = std::ceil(x0 / step) * step; gx <= x1 + 1e-9; gx += step) {
      out_ += "<line class=\"grid\" x1=\"" + n2(sx(gx)) + "\" y1=\"" + n2(top_) + "\" x2=\"" + n2(sx(gx)) + "\" y2=\"" + n2(top_ + h) +
              "\" stroke=\"#e4e4e4\" stroke-width=\"0.8\"/>\n";
      text(sx(gx) - 4, top_ + h + 12, 9, tickLabel(gx, step), "grid-label", "fill=\"#777777\"");
    }
    for (double gy = std::ceil(y0 / step) * step; gy <= y1 + 1e-9; gy += step) {
      out_ += "<line class=\"grid\" x1=\"" + n2(left_) + "\" y1=\"" + n2(sy(gy)) + "\" x2=\"" + n2(left_ + w) + "\" y2=\"" + n2(sy(gy)) +
              "\" stroke=\"#e4e4e4\" stroke-width=\"0.8\"/>\n";
      text(left_ - 16, sy(gy) + 3, 9, tickLabel(gy, step), "grid-label", "fill=\"#777777\"");
    }
    text(left_ + w - 30, top_ + h + 24, 9, "metres", "grid-label", "fill=\"#777777\"");
    // The arena as the world file gives it (what lies outside it, a robot gone astray, stays visible).
    if (const auto& a = tr_.world.arena) {
      out_ += "<rect class=\"arena\" x=\"" + n2(sx(a->first.x)) + "\" y=\"" + n2(sy(a->second.y)) + "\" width=\"" +
              n2((a->second.x - a->first.x) * scale_) + "\" height=\"" + n2((a->second.y - a->first.y) * scale_) +
              "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1.5\"/>\n";
    }
    obstacles();
    facts();
    places();
    robots();
    labels();
    out_ += "</g>\n";
    return top_ + h + 24;
  }

  void obstacles() {
    for (const Obstacle& o : tr_.world.obstacles) {
      const std::string title = "<title>" + xml(o.name) + "</title>";
      Vec2 middle = o.shape.center;
      if (o.shape.kind == Shape::Kind::Circle) {
        out_ += "<circle class=\"obstacle\" cx=\"" + n2(sx(o.shape.center.x)) + "\" cy=\"" + n2(sy(o.shape.center.y)) + "\" r=\"" +
                n2(o.shape.radius * scale_) + "\" fill=\"#9e9e9e\" stroke=\"#616161\">" + title + "</circle>\n";
      } else {
        std::string points;
        middle = {0, 0};
        for (const Vec2& p : o.shape.points) {
          points += (points.empty() ? "" : " ") + px(p);
          middle.x += p.x / static_cast<double>(o.shape.points.size());
          middle.y += p.y / static_cast<double>(o.shape.points.size());
        }
        out_ += "<polygon class=\"obstacle\" points=\"" + points + "\" fill=\"#9e9e9e\" stroke=\"#616161\">" + title + "</polygon>\n";
      }
      text(sx(middle.x) - textWidth(o.name, 9) / 2, sy(middle.y) + 3, 9, xml(o.name), "obstacle-label", "fill=\"#303030\"");
      taken_.push_back(textBox(sx(middle.x) - textWidth(o.name, 9) / 2, sy(middle.y) + 3, 9, textWidth(o.name, 9)));
    }
  }

  void facts() {
    for (const FactSite& f : tr_.world.facts) {
      const std::string label = xml(f.knowledge + ": " + f.fact);
      out_ += "<circle class=\"fact-site\" cx=\"" + n2(sx(f.at.x)) + "\" cy=\"" + n2(sy(f.at.y)) + "\" r=\"" + n2(f.radius * scale_) +
              "\" fill=\"none\" stroke=\"#b8860b\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"><title>" + label + "</title></circle>\n";
      const double r = f.radius * scale_;
      pending_.push_back({sx(f.at.x), sy(f.at.y), 9, label, "fact-label", "fill=\"#8b6508\"",
                          {{r + 3, 3}, {-r - 3 - textWidth(f.knowledge + ": " + f.fact, 9), 3}, {-textWidth(f.knowledge + ": " + f.fact, 9) / 2, -r - 4},
                           {-textWidth(f.knowledge + ": " + f.fact, 9) / 2, r + 11}}});
    }
  }

  void places() {
    for (const Place& p : tr_.world.places) {
      out_ += "<rect class=\"place\" x=\"" + n2(sx(p.at.x) - 3) + "\" y=\"" + n2(sy(p.at.y) - 3) +
              "\" width=\"6\" height=\"6\" fill=\"#000000\"><title>" + xml(p.name) + "</title></rect>\n";
      taken_.push_back({sx(p.at.x) - 3, sy(p.at.y) - 3, sx(p.at.x) + 3, sy(p.at.y) + 3});
      pending_.push_back({sx(p.at.x), sy(p.at.y), 10, xml(p.name), "place-label", "", pointSpots(textWidth(p.name, 10), false)});
    }
  }

  void robots() {
    // Robots that end where another ended (within a triangle's size) share one label.
    struct Group {
      double x, y;
      std::vector<std::size_t> robots;
    };
    std::vector<Group> groups;
    for (std::size_t r = 0; r < tr_.robots.size(); ++r) {
      const char* colour = robotColour(r);
      std::string points;
      std::optional<Vec2> first;
      for (const PoseSample& s : tr_.poses) {
        if (r >= s.poses.size() || !std::isfinite(s.poses[r].x) || !std::isfinite(s.poses[r].y)) continue;
        points += (points.empty() ? "" : " ") + px({s.poses[r].x, s.poses[r].y});
        if (!first) first = Vec2{s.poses[r].x, s.poses[r].y};
      }
      const std::string name = xml(tr_.robots[r].name);
      if (!points.empty()) {
        out_ += "<polyline class=\"trajectory\" points=\"" + points + "\" fill=\"none\" stroke=\"" + colour +
                "\" stroke-width=\"2\" stroke-linejoin=\"round\" stroke-opacity=\"0.85\"><title>" + name + "</title></polyline>\n";
        out_ += "<circle class=\"start\" cx=\"" + n2(sx(first->x)) + "\" cy=\"" + n2(sy(first->y)) + "\" r=\"4\" fill=\"#ffffff\" stroke=\"" +
                colour + "\" stroke-width=\"2\"/>\n";
      }
      const std::optional<Pose> last = lastPose(r);
      if (!last || !std::isfinite(last->x) || !std::isfinite(last->y)) continue;
      // A triangle pointing along the heading (screen y is flipped, hence the minus on sin).
      const double cx = sx(last->x), cy = sy(last->y), th = std::isfinite(last->theta) ? last->theta : 0;
      auto corner = [&](double angle, double radius) {
        return n2(cx + radius * std::cos(th + angle)) + "," + n2(cy - radius * std::sin(th + angle));
      };
      out_ += "<polygon class=\"robot\" points=\"" + corner(0, 10) + " " + corner(2.5, 7) + " " + corner(-2.5, 7) + "\" fill=\"" + colour +
              "\" stroke=\"#000000\" stroke-width=\"0.8\"><title>" + name + "</title></polygon>\n";
      taken_.push_back({cx - 10, cy - 10, cx + 10, cy + 10});
      const auto near = std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return std::hypot(g.x - cx, g.y - cy) < 12; });
      if (near == groups.end()) groups.push_back({cx, cy, {r}});
      else near->robots.push_back(r);
      if (crashTime(r)) {
        cross(cx, cy, 9, "crash-pose", 2.5);
        taken_.push_back({cx - 9, cy - 9, cx + 9, cy + 9});
      }
    }
    for (const Group& g : groups) {
      std::string names;
      for (std::size_t r : g.robots) names += (names.empty() ? "" : ", ") + tr_.robots[r].name;
      if (g.robots.size() > 3) {
        names = std::to_string(g.robots.size()) + " robots: " + tr_.robots[g.robots.front()].name + " ... " + tr_.robots[g.robots.back()].name;
      }
      const std::string colour = g.robots.size() == 1 ? robotColour(g.robots.front()) : "#333333";
      pending_.push_back({g.x, g.y, 10, xml(names), "robot-label", "fill=\"" + colour + "\"", pointSpots(textWidth(names, 10), true)});
    }
  }

  // A label of the world, drawn once every mark is: at the first of its spots (offsets of its
  // baseline's start from its anchor) where it covers nothing drawn before it.
  struct Label {
    double x, y, size;
    std::string escaped;
    const char* cls;
    std::string extra;
    std::vector<std::pair<double, double>> spots;
  };
  std::vector<Label> pending_;

  // Spots around a point for a label `width` wide: beside it, then under or over it, then further
  // down or up, a line at a time. A robot's label goes under it first, a place's over it.
  static std::vector<std::pair<double, double>> pointSpots(double width, bool under) {
    std::vector<std::pair<double, double>> spots;
    const std::pair<double, double> below{9, 14}, above{6, -6};
    spots.push_back(under ? below : above);
    spots.push_back(under ? above : below);
    spots.insert(spots.end(), {{-width - 9, 14}, {-width - 6, -6}, {-width / 2, 22}, {-width / 2, -13}});
    for (int k = 1; k <= 6; ++k) spots.insert(spots.end(), {{9, 14 + 12.0 * k}, {6, -6 - 12.0 * k}});
    return spots;
  }

  static Box textBox(double x, double y, double size, double width) { return {x, y - size * 0.8, x + width, y + size * 0.25}; }
  bool overlapsTaken(const Box& b) const {
    return std::any_of(taken_.begin(), taken_.end(), [&](const Box& o) { return b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1; });
  }

  void labels() {
    for (const Label& l : pending_) {
      const double width = textWidth(unescaped(l.escaped), l.size);
      std::pair<double, double> at = l.spots.back();
      for (const auto& spot : l.spots) {
        if (!overlapsTaken(textBox(l.x + spot.first, l.y + spot.second, l.size, width))) {
          at = spot;
          break;
        }
      }
      taken_.push_back(textBox(l.x + at.first, l.y + at.second, l.size, width));
      text(l.x + at.first, l.y + at.second, l.size, l.escaped, l.cls, l.extra);
    }
  }

  // The text an escaped label stands for, to measure it.
  static std::string unescaped(const std::string& escaped) {
    std::string out;
    for (std::size_t i = 0; i < escaped.size(); ++i) {
      if (escaped[i] == '&') {
        const std::size_t end = escaped.find(';', i);
        out += '?';
        i = end == std::string::npos ? escaped.size() : end;
      } else {
        out += escaped[i];
      }
    }
    return out;
  }

  void cross(double x, double y, double half, const char* cls, double width) {
    out_ += "<path class=\"" + std::string(cls) + "\" d=\"M" + n2(x - half) + "," + n2(y - half) + " L" + n2(x + half) + "," + n2(y + half) +
            " M" + n2(x - half) + "," + n2(y + half) + " L" + n2(x + half) + "," + n2(y - half) + "\" stroke=\"#d62728\" stroke-width=\"" +
            n2(width) + "\" fill=\"none\"/>\n";
  }

  double tx(double t) const {
    const double x0 = kMargin + kLabelColumn, x1 = kWidth - kMargin;
    return x0 + std::clamp(t / end_, 0.0, 1.0) * (x1 - x0);
  }

  // A band from t0 to t1 on a row, with its name inside when it fits.
  void band(const char* cls, double t0, double t1, double y, double h, const char* fill, const std::string& name, double fontSize,
            const std::string& title = {}, const std::string& shorter = {}) {
    const double x0 = tx(t0), w = std::max(tx(t1) - x0, 0.5);
    out_ += "<rect class=\"" + std::string(cls) + "\" x=\"" + n2(x0) + "\" y=\"" + n2(y) + "\" width=\"" + n2(w) + "\" height=\"" + n2(h) +
            "\" fill=\"" + fill + "\" stroke=\"#ffffff\" stroke-width=\"0.8\"><title>" + xml(title.empty() ? name : title) + " (" +
            fixed(t0, 3) + " s to " + fixed(t1, 3) + " s)</title></rect>\n";
    // The name when it fits, else the shorter one when that does.
    for (const std::string* label : {&name, &shorter}) {
      if (label->empty() || textWidth(*label, fontSize) + 6 > w) continue;
      text(x0 + 3, y + h / 2 + fontSize * 0.35, fontSize, xml(*label), "band-label");
      break;
    }
  }

  double timeline(double top) {
    const double x0 = tx(0), x1 = tx(end_);
    out_ += "<g class=\"timeline\">\n";
    text(kMargin, top, 12, "Timeline", "section-title", "font-weight=\"bold\"");
    const double axis = top + 14;
    double bottom = axis + 8;
    for (std::size_t r = 0; r < tr_.robots.size(); ++r) bottom += rowHeight(r);
    out_ += "<line class=\"time-axis\" x1=\"" + n2(x0) + "\" y1=\"" + n2(axis) + "\" x2=\"" + n2(x1) + "\" y2=\"" + n2(axis) +
            "\" stroke=\"#000000\"/>\n";
    const double step = niceStep(end_, 12);
    for (double t = 0; t <= end_ + 1e-9; t += step) {
      out_ += "<line class=\"time-tick\" x1=\"" + n2(tx(t)) + "\" y1=\"" + n2(axis - 4) + "\" x2=\"" + n2(tx(t)) + "\" y2=\"" + n2(bottom) +
              "\" stroke=\"#dddddd\" stroke-width=\"0.8\"/>\n";
      text(tx(t) - 6, axis - 6, 9, tickLabel(t, step) + (t == 0 ? " s" : ""), "time-label");
    }
    double y = axis + 8;
    for (std::size_t r = 0; r < tr_.robots.size(); ++r) {
      row(r, y);
      y += rowHeight(r);
    }
    // Violations of no robot in particular cross every row.
    for (const TraceEvent& e : tr_.events) {
      if (e.kind == TraceEvent::Kind::Violation && e.robot >= tr_.robots.size()) violation(e, axis, bottom);
    }
    out_ += "</g>\n";
    return bottom;
  }

  void violation(const TraceEvent& e, double y0, double y1) {
    out_ += "<line class=\"violation\" x1=\"" + n2(tx(e.t)) + "\" y1=\"" + n2(y0) + "\" x2=\"" + n2(tx(e.t)) + "\" y2=\"" + n2(y1) +
            "\" stroke=\"#d62728\" stroke-width=\"1.5\"><title>" + xml(e.label.empty() ? e.detail : e.label) + "</title></line>\n";
  }

  double rowHeight(std::size_t r) const {
    const std::size_t n = lanes_[r].size();
    return kRowHeight + kLaneHeight * static_cast<double>(n > 1 ? n - 1 : 0);
  }

  // "ReportPapers: leader" for the role "leader of SlaveTeam.Report.ReportPapers#2" in that block.
  static std::string roleText(const std::string& block, const std::string& role) {
    if (block.empty()) return role;
    std::string name = block.substr(block.rfind('.') == std::string::npos ? 0 : block.rfind('.') + 1);
    name = name.substr(0, name.find('#'));
    return name + ": " + (role.rfind("leader of ", 0) == 0 ? "leader" : role);
  }

  void row(std::size_t r, double y) {
    const std::optional<double> crashed = crashTime(r);
    const std::vector<std::string>& blocks = lanes_[r];
    const double h = rowHeight(r);
    const double ticks = y + 23 + kLaneHeight * static_cast<double>(std::max<std::size_t>(blocks.size(), 1)) - 1;  // messages and facts
    const double stop = crashed ? *crashed : end_;
    out_ += "<rect class=\"row-swatch\" x=\"" + n2(kMargin) + "\" y=\"" + n2(y + 8) + "\" width=\"10\" height=\"10\" fill=\"" + robotColour(r) + "\"/>\n";
    text(kMargin + 14, y + 17, 11, xml(tr_.robots[r].name), "row-label");
    if (!tr_.robots[r].team.empty()) text(kMargin + 14, y + 29, 8, xml(tr_.robots[r].team), "row-team", "fill=\"#666666\"");
    out_ += "<line class=\"row-base\" x1=\"" + n2(tx(0)) + "\" y1=\"" + n2(y + h - 1) + "\" x2=\"" + n2(tx(end_)) + "\" y2=\"" +
            n2(y + h - 1) + "\" stroke=\"#cccccc\"/>\n";
    // A mode holds from its event to the next mode (or the crash, or the end); a role in a block,
    // on that block's lane, to the robot's next role event in the same block.
    const TraceEvent* mode = nullptr;
    std::vector<const TraceEvent*> role(blocks.size(), nullptr);
    auto closeMode = [&](double t) {
      if (mode != nullptr && t > mode->t) band("mode-band", mode->t, t, y + 3, 18, modeColour(mode->detail), mode->detail, 10);
    };
    auto closeRole = [&](std::size_t lane, double t) {
      const TraceEvent* e = role[lane];
      if (e == nullptr || e->detail.empty() || !(t > e->t)) return;
      band("role-band", e->t, t, y + 23 + kLaneHeight * static_cast<double>(lane), 10, "#cfd8dc", roleText(e->block, e->detail), 8,
           tr_.robots[r].name + (e->block.empty() ? "" : ", " + e->block) + ": " + e->detail,
           e->detail.rfind("leader of ", 0) == 0 ? "leader" : e->detail);
    };
    for (const TraceEvent& e : tr_.events) {
      if (e.robot != r || e.t > stop) continue;
      if (e.kind == TraceEvent::Kind::Mode) closeMode(e.t), mode = &e;
      if (e.kind == TraceEvent::Kind::Role) {
        const auto lane = static_cast<std::size_t>(std::find(blocks.begin(), blocks.end(), e.block) - blocks.begin());
        closeRole(lane, e.t);
        role[lane] = &e;
      }
    }
    closeMode(stop);
    for (std::size_t lane = 0; lane < blocks.size(); ++lane) closeRole(lane, stop);
    for (const TraceEvent& e : tr_.events) {
      if (e.robot != r) continue;
      const double x = tx(e.t);
      const std::string what = xml(e.detail) + (e.peer < tr_.robots.size() ? " / " + xml(tr_.robots[e.peer].name) : "") + " at " + fixed(e.t, 3) + " s";
      if (e.kind == TraceEvent::Kind::Send) {
        out_ += "<line class=\"msg-sent\" x1=\"" + n2(x) + "\" y1=\"" + n2(ticks + 1) + "\" x2=\"" + n2(x) + "\" y2=\"" + n2(ticks + 6) +
                "\" stroke=\"#888888\" stroke-width=\"1\"><title>sent " + what + "</title></line>\n";
      } else if (e.kind == TraceEvent::Kind::Drop) {
        out_ += "<line class=\"msg-lost\" x1=\"" + n2(x) + "\" y1=\"" + n2(ticks) + "\" x2=\"" + n2(x) + "\" y2=\"" + n2(ticks + 8) +
                "\" stroke=\"#d62728\" stroke-width=\"1.5\"><title>lost " + what + "</title></line>\n";
      } else if (e.kind == TraceEvent::Kind::Fact) {
        out_ += "<path class=\"fact-found\" d=\"M" + n2(x) + "," + n2(ticks + 0.5) + " l3,3 l-3,3 l-3,-3 z\" fill=\"#b8860b\"><title>found " + what +
                "</title></path>\n";
      } else if (e.kind == TraceEvent::Kind::Violation) {
        violation(e, y, y + h - 2);
      }
    }
    if (crashed) {
      out_ += "<g class=\"crash\"><title>crash at " + fixed(*crashed, 3) + " s</title>\n";
      cross(tx(*crashed), y + 12, 6, "crash-mark", 2.5);
      text(tx(*crashed) + 9, y + 16, 10, "crash", "crash-label", "fill=\"#d62728\" font-weight=\"bold\"");
      out_ += "</g>\n";
    }
  }

  // Keys, laid out left to right and wrapped: robots, then the marks, then the modes' colours.
  double legend(double top) {
    out_ += "<g class=\"legend\">\n";
    double x = kMargin, y = top;
    auto next = [&](double width) {
      if (x + width > kWidth - kMargin) x = kMargin, y += 18;
      const double at = x;
      x += width;
      return at;
    };
    for (std::size_t r = 0; r < tr_.robots.size(); ++r) {
      const double at = next(30 + textWidth(tr_.robots[r].name, 10));
      out_ += "<line x1=\"" + n2(at) + "\" y1=\"" + n2(y - 4) + "\" x2=\"" + n2(at + 18) + "\" y2=\"" + n2(y - 4) + "\" stroke=\"" +
              robotColour(r) + "\" stroke-width=\"3\"/>\n";
      text(at + 22, y, 10, xml(tr_.robots[r].name), "legend-label");
    }
    x = kMargin, y += 20;
    auto key = [&](const std::string& mark, const char* label) {
      const double at = next(36 + textWidth(label, 10));
      std::string m = mark;
      for (std::size_t i; (i = m.find("@X")) != std::string::npos;) m.replace(i, 2, n2(at));
      for (std::size_t i; (i = m.find("@Y")) != std::string::npos;) m.replace(i, 2, n2(y));
      out_ += m + "\n";
      text(at + 22, y, 10, label, "legend-label");
    };
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(0,-10)\" width=\"18\" height=\"10\" fill=\"#aec7e8\"/>", "mode");
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(0,-8)\" width=\"18\" height=\"6\" fill=\"#cfd8dc\"/>", "role in a group block");
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(8,-9)\" width=\"1.5\" height=\"7\" fill=\"#888888\"/>", "message sent");
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(8,-9)\" width=\"2\" height=\"8\" fill=\"#d62728\"/>", "message lost");
    key("<path d=\"M@X,@Y m4,-9 l8,8 m-8,0 l8,-8\" stroke=\"#d62728\" stroke-width=\"2.5\" fill=\"none\"/>", "crash");
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(8,-11)\" width=\"1.5\" height=\"12\" fill=\"#d62728\"/>", "violation");
    key("<path d=\"M@X,@Y m9,-9 l3,3 l-3,3 l-3,-3 z\" fill=\"#b8860b\"/>", "fact found");
    key("<circle cx=\"@X\" cy=\"@Y\" transform=\"translate(9,-4)\" r=\"6\" fill=\"none\" stroke=\"#b8860b\" stroke-dasharray=\"3 2\"/>", "fact site");
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(2,-10)\" width=\"12\" height=\"10\" fill=\"#9e9e9e\"/>", "obstacle");
    key("<rect x=\"@X\" y=\"@Y\" transform=\"translate(6,-7)\" width=\"6\" height=\"6\" fill=\"#000000\"/>", "place");
    if (!modes_.empty()) {
      x = kMargin, y += 20;
      std::vector<std::pair<std::size_t, std::string>> ordered;
      for (const auto& [name, index] : modes_) ordered.emplace_back(index, name);
      std::sort(ordered.begin(), ordered.end());
      for (const auto& [index, name] : ordered) {
        const double at = next(36 + textWidth(name, 10));
        out_ += "<rect x=\"" + n2(at) + "\" y=\"" + n2(y - 10) + "\" width=\"18\" height=\"10\" fill=\"" +
                kModeColours[index % std::size(kModeColours)] + "\"/>\n";
        text(at + 22, y, 10, xml(name), "legend-label");
      }
    }
    out_ += "</g>\n";
    return y;
  }
};

}  // namespace

std::string renderSvg(const SimTrace& trace) { return Picture(trace).render(); }

}  // namespace semo::runtime
