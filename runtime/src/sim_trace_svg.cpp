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
constexpr double kRowHeight = 44;
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
  explicit Picture(const SimTrace& trace) : tr_(trace) {
    for (const TraceEvent& e : tr_.events) {
      if (e.kind == TraceEvent::Kind::Mode) modeColour(e.detail);
      end_ = std::max(end_, e.t);
    }
    for (const PoseSample& s : tr_.poses) end_ = std::max(end_, s.t);
    if (tr_.duration > 0) end_ = tr_.duration;
    if (!(end_ > 0) || !std::isfinite(end_)) end_ = 1;
  }

  std::string render() {
    double y = kMargin;
    text(kMargin, y + 4, 14, xml(title()), "title", "font-weight=\"bold\"");
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
  std::string out_;
  double end_ = 0;  // the timeline's last second
  std::map<std::string, std::size_t> modes_;  // mode -> colour, in order of first appearance
  // World -> picture: x' = left + (x - minX)·scale, y' = top + (maxY - y)·scale (y points up).
  double minX_ = 0, maxY_ = 0, scale_ = 1, left_ = 0, top_ = 0;

  std::string px(Vec2 p) const { return n2(left_ + (p.x - minX_) * scale_) + "," + n2(top_ + (maxY_ - p.y) * scale_); }
  double sx(double x) const { return left_ + (x - minX_) * scale_; }
  double sy(double y) const { return top_ + (maxY_ - y) * scale_; }

  const char* modeColour(const std::string& mode) {
    auto it = modes_.try_emplace(mode, modes_.size()).first;
    return kModeColours[it->second % std::size(kModeColours)];
  }
  static const char* robotColour(std::size_t r) { return kRobotColours[r % std::size(kRobotColours)]; }

  std::string title() const {
    std::string t = tr_.mission.empty() ? "simulated run" : tr_.mission;
    t += "  (seed " + std::to_string(tr_.seed) + ", " + fixed(tr_.duration, 1) + " s";
    if (!tr_.faults.empty()) t += ", " + tr_.faults;
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
    }
  }

  void facts() {
    for (const FactSite& f : tr_.world.facts) {
      const std::string label = xml(f.knowledge + ": " + f.fact);
      out_ += "<circle class=\"fact-site\" cx=\"" + n2(sx(f.at.x)) + "\" cy=\"" + n2(sy(f.at.y)) + "\" r=\"" + n2(f.radius * scale_) +
              "\" fill=\"none\" stroke=\"#b8860b\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"><title>" + label + "</title></circle>\n";
      text(sx(f.at.x) + f.radius * scale_ + 3, sy(f.at.y) + 3, 9, label, "fact-label", "fill=\"#8b6508\"");
    }
  }

  void places() {
    for (const Place& p : tr_.world.places) {
      out_ += "<g class=\"place\"><rect x=\"" + n2(sx(p.at.x) - 3) + "\" y=\"" + n2(sy(p.at.y) - 3) +
              "\" width=\"6\" height=\"6\" fill=\"#000000\"/>";
      out_ += "<text x=\"" + n2(sx(p.at.x) + 6) + "\" y=\"" + n2(sy(p.at.y) - 5) + "\" font-size=\"10\">" + xml(p.name) + "</text></g>\n";
    }
  }

  void robots() {
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
      text(cx + 9, cy + 14, 10, name, "robot-label", std::string("fill=\"") + colour + "\"");
      if (crashTime(r)) cross(cx, cy, 9, "crash-pose", 2.5);
    }
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
  void band(const char* cls, double t0, double t1, double y, double h, const char* fill, const std::string& name, double fontSize) {
    const double x0 = tx(t0), w = std::max(tx(t1) - x0, 0.5);
    out_ += "<rect class=\"" + std::string(cls) + "\" x=\"" + n2(x0) + "\" y=\"" + n2(y) + "\" width=\"" + n2(w) + "\" height=\"" + n2(h) +
            "\" fill=\"" + fill + "\" stroke=\"#ffffff\" stroke-width=\"0.8\"><title>" + xml(name) + " (" + fixed(t0, 1) + " s to " +
            fixed(t1, 1) + " s)</title></rect>\n";
    if (textWidth(name, fontSize) + 6 <= w) text(x0 + 3, y + h / 2 + fontSize * 0.35, fontSize, xml(name), "band-label");
  }

  double timeline(double top) {
    const double x0 = tx(0), x1 = tx(end_);
    out_ += "<g class=\"timeline\">\n";
    text(kMargin, top, 12, "Timeline", "section-title", "font-weight=\"bold\"");
    const double axis = top + 14;
    const double bottom = axis + 8 + kRowHeight * static_cast<double>(tr_.robots.size());
    out_ += "<line class=\"time-axis\" x1=\"" + n2(x0) + "\" y1=\"" + n2(axis) + "\" x2=\"" + n2(x1) + "\" y2=\"" + n2(axis) +
            "\" stroke=\"#000000\"/>\n";
    const double step = niceStep(end_, 12);
    for (double t = 0; t <= end_ + 1e-9; t += step) {
      out_ += "<line class=\"time-tick\" x1=\"" + n2(tx(t)) + "\" y1=\"" + n2(axis - 4) + "\" x2=\"" + n2(tx(t)) + "\" y2=\"" + n2(bottom) +
              "\" stroke=\"#dddddd\" stroke-width=\"0.8\"/>\n";
      text(tx(t) - 6, axis - 6, 9, tickLabel(t, step) + (t == 0 ? " s" : ""), "time-label");
    }
    for (std::size_t r = 0; r < tr_.robots.size(); ++r) row(r, axis + 8 + kRowHeight * static_cast<double>(r));
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

  void row(std::size_t r, double y) {
    const std::optional<double> crashed = crashTime(r);
    const double stop = crashed ? *crashed : end_;
    out_ += "<rect class=\"row-swatch\" x=\"" + n2(kMargin) + "\" y=\"" + n2(y + 8) + "\" width=\"10\" height=\"10\" fill=\"" + robotColour(r) + "\"/>\n";
    text(kMargin + 14, y + 17, 11, xml(tr_.robots[r].name), "row-label");
    if (!tr_.robots[r].team.empty()) text(kMargin + 14, y + 29, 8, xml(tr_.robots[r].team), "row-team", "fill=\"#666666\"");
    out_ += "<line class=\"row-base\" x1=\"" + n2(tx(0)) + "\" y1=\"" + n2(y + kRowHeight - 1) + "\" x2=\"" + n2(tx(end_)) + "\" y2=\"" +
            n2(y + kRowHeight - 1) + "\" stroke=\"#cccccc\"/>\n";
    // Modes and roles hold from their event to the next one of their kind (or the crash, or the end).
    const TraceEvent* mode = nullptr;
    const TraceEvent* role = nullptr;
    auto closeMode = [&](double t) {
      if (mode != nullptr && t > mode->t) band("mode-band", mode->t, t, y + 3, 18, modeColour(mode->detail), mode->detail, 10);
    };
    auto closeRole = [&](double t) {
      if (role != nullptr && !role->detail.empty() && t > role->t) band("role-band", role->t, t, y + 23, 10, "#cfd8dc", role->detail, 8);
    };
    for (const TraceEvent& e : tr_.events) {
      if (e.robot != r || e.t > stop) continue;
      switch (e.kind) {
        case TraceEvent::Kind::Mode: closeMode(e.t), mode = &e; break;
        case TraceEvent::Kind::Role: closeRole(e.t), role = &e; break;
        default: break;
      }
    }
    closeMode(stop);
    closeRole(stop);
    for (const TraceEvent& e : tr_.events) {
      if (e.robot != r) continue;
      const double x = tx(e.t);
      const std::string what = xml(e.detail) + (e.peer < tr_.robots.size() ? " / " + xml(tr_.robots[e.peer].name) : "") + " at " + fixed(e.t, 3) + " s";
      if (e.kind == TraceEvent::Kind::Send) {
        out_ += "<line class=\"msg-sent\" x1=\"" + n2(x) + "\" y1=\"" + n2(y + 35) + "\" x2=\"" + n2(x) + "\" y2=\"" + n2(y + 40) +
                "\" stroke=\"#888888\" stroke-width=\"1\"><title>sent " + what + "</title></line>\n";
      } else if (e.kind == TraceEvent::Kind::Drop) {
        out_ += "<line class=\"msg-lost\" x1=\"" + n2(x) + "\" y1=\"" + n2(y + 34) + "\" x2=\"" + n2(x) + "\" y2=\"" + n2(y + 42) +
                "\" stroke=\"#d62728\" stroke-width=\"1.5\"><title>lost " + what + "</title></line>\n";
      } else if (e.kind == TraceEvent::Kind::Fact) {
        out_ += "<path class=\"fact-found\" d=\"M" + n2(x) + "," + n2(y + 34.5) + " l3,3 l-3,3 l-3,-3 z\" fill=\"#b8860b\"><title>found " + what +
                "</title></path>\n";
      } else if (e.kind == TraceEvent::Kind::Violation) {
        violation(e, y, y + kRowHeight - 2);
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
