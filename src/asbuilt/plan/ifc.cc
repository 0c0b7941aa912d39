#include "asbuilt/plan/ifc.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/hash.h"

namespace asbuilt {
namespace {

// A mitre of two walls' outer faces farther from their corner than this many
// thicknesses (walls folding back on each other) leaves square ends instead,
// as the drawings bevel there.
constexpr double kIfcMitreLimit = 4.0;
// An opening's box reaches this far beyond both wall faces, so it cuts cleanly.
constexpr double kOpeningMarginM = 0.05;
// Thickness of the panel that stands for a door leaf or a window.
constexpr double kPanelThicknessM = 0.05;

// ---- STEP (ISO 10303-21) text ----

// A REAL: always with a decimal point ("2.", "0.25", "1.E-05"), shortest
// text that reads back to the same double.
std::string StepReal(double x) {
  if (x == 0) return "0.";
  std::string s = fmt::format("{}", x);
  const size_t e = s.find_first_of("eE");
  std::string mantissa = e == std::string::npos ? s : s.substr(0, e);
  std::string exponent;
  if (e != std::string::npos) exponent = fmt::format("E{}", s.substr(e + 1));
  if (mantissa.find('.') == std::string::npos) mantissa += '.';
  return mantissa + exponent;
}

// A STRING from UTF-8: printable ASCII as is (' and \ doubled), every other
// character as \X2\hhhh\X0\ (or \X4\ beyond the BMP); bad UTF-8 → U+FFFD.
std::string StepString(std::string_view text) {
  std::string out = "'";
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      if (c == '\'') {
        out += "''";
      } else if (c == '\\') {
        out += "\\\\";
      } else {
        out += static_cast<char>(c);
      }
      ++i;
      continue;
    }
    std::uint32_t cp = c;
    size_t n = 1;
    if ((c & 0xE0) == 0xC0) {
      cp = c & 0x1F, n = 2;
    } else if ((c & 0xF0) == 0xE0) {
      cp = c & 0x0F, n = 3;
    } else if ((c & 0xF8) == 0xF0) {
      cp = c & 0x07, n = 4;
    } else if (c >= 0x80) {
      cp = 0xFFFD;
    }
    bool ok = i + n <= text.size();
    for (size_t k = 1; ok && k < n; ++k) {
      const unsigned char cc = static_cast<unsigned char>(text[i + k]);
      if ((cc & 0xC0) != 0x80) ok = false;
      cp = (cp << 6) | (cc & 0x3F);
    }
    if (!ok) cp = 0xFFFD, n = 1;
    i += n;
    out += cp <= 0xFFFF ? fmt::format("\\X2\\{:04X}\\X0\\", cp) : fmt::format("\\X4\\{:08X}\\X0\\", cp);
  }
  return out + "'";
}

std::string Ref(int id) { return fmt::format("#{}", id); }
std::string Refs(const std::vector<int>& ids) {
  std::string out = "(";
  for (size_t i = 0; i < ids.size(); ++i) {
    if (i) out += ',';
    out += Ref(ids[i]);
  }
  return out + ")";
}
std::string Reals(std::initializer_list<double> values) {
  std::string out = "(";
  for (double v : values) {
    if (out.size() > 1) out += ',';
    out += StepReal(v);
  }
  return out + ")";
}

// The DATA section: numbered entity instances in the order they are added.
class StepData {
 public:
  int Add(std::string_view type, const std::string& args) {
    text_ += fmt::format("#{}={}({});\n", ++last_, type, args);
    return last_;
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  int last_ = 0;
};

// Deterministic GlobalIds: the n-th id of a plan is a hash of the plan's
// content and n, so the same plan gives the same ids and different plans
// different ones.
class GuidSource {
 public:
  explicit GuidSource(std::string_view content) {
    std::uint64_t h = 0xCBF29CE484222325ULL;  // FNV-1a, then mixed.
    for (char c : content) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001B3ULL;
    seed_ = SplitMix64(h);
  }
  std::string Next() {
    const std::uint64_t high = SplitMix64(seed_ + 2 * count_);
    const std::uint64_t low = SplitMix64(seed_ + 2 * count_ + 1);
    ++count_;
    return StepString(IfcGuid(high, low));
  }

 private:
  std::uint64_t seed_ = 0;
  std::uint64_t count_ = 0;
};

// ---- The plan, checked and with every dimension resolved ----

struct ResolvedWall {
  double length_m = 0, thickness_m = 0, height_m = 0;
  bool degenerate = false;  // Zero length: an IfcWall without geometry.
  bool thickness_default = false, height_default = false;
  Vec2 dir = Vec2::UnitX();  // Unit vector start → end.
  // Footprint in the wall's frame (x along, y into the room), counter-clockwise;
  // empty for a degenerate wall.
  std::vector<Vec2> footprint;
};

std::string PointText(const Vec2& p) { return fmt::format("({}, {})", p.x(), p.y()); }
bool Finite(const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

void CheckModellable(const Plan& plan, const std::string& name) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: cannot model the plan: {}", name, what)); };
  auto check_size = [&](const std::optional<double>& v, const std::string& field) {
    if (v && !std::isfinite(*v)) fail(fmt::format("{} = {} is not finite", field, *v));
  };
  for (size_t i = 0; i < plan.walls.size(); ++i) {
    const PlanWall& w = plan.walls[i];
    if (!Finite(w.start)) fail(fmt::format("walls[{}].start = {} is not finite", i, PointText(w.start)));
    if (!Finite(w.end)) fail(fmt::format("walls[{}].end = {} is not finite", i, PointText(w.end)));
    check_size(w.thickness, fmt::format("walls[{}].thickness", i));
    check_size(w.height, fmt::format("walls[{}].height", i));
  }
  for (size_t i = 0; i < plan.openings.size(); ++i) {
    const PlanOpening& o = plan.openings[i];
    if (o.wall < 0 || o.wall >= static_cast<int>(plan.walls.size())) {
      fail(fmt::format("openings[{}].wall = {} is not a wall of the plan ({} walls)", i, o.wall, plan.walls.size()));
    }
    if (!Finite(o.start)) fail(fmt::format("openings[{}].start = {} is not finite", i, PointText(o.start)));
    if (!Finite(o.end)) fail(fmt::format("openings[{}].end = {} is not finite", i, PointText(o.end)));
    if (!(std::isfinite(o.width) && o.width > 0)) fail(fmt::format("openings[{}].width = {}, must be > 0", i, o.width));
    check_size(o.height, fmt::format("openings[{}].height", i));
    check_size(o.sill, fmt::format("openings[{}].sill", i));
  }
  for (size_t i = 0; i < plan.rooms.size(); ++i) {
    const PlanRoom& r = plan.rooms[i];
    for (size_t k = 0; k < r.polygon.size(); ++k) {
      if (!Finite(r.polygon[k])) {
        fail(fmt::format("rooms[{}].polygon[{}] = {} is not finite", i, k, PointText(r.polygon[k])));
      }
    }
  }
}

// A size from the plan when it gives a positive one, else the default.
std::pair<double, bool> SizeOr(const std::optional<double>& v, double fallback) {
  if (v && *v > 0) return {*v, false};
  return {fallback, true};
}

std::vector<ResolvedWall> ResolveWalls(const Plan& plan, const IfcOptions& o) {
  const int n = static_cast<int>(plan.walls.size());
  std::vector<ResolvedWall> walls(n);
  std::vector<Vec2> outer_start(n), outer_end(n);  // World xy.
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    ResolvedWall& r = walls[i];
    r.length_m = w.Length();
    r.degenerate = !(r.length_m > 1e-9);
    if (!r.degenerate) r.dir = (w.end - w.start) / r.length_m;
    std::tie(r.thickness_m, r.thickness_default) = SizeOr(w.thickness, o.default_wall_thickness_m);
    std::tie(r.height_m, r.height_default) = SizeOr(w.height, o.default_wall_height_m);
    outer_start[i] = w.start - r.thickness_m * Perp(r.dir);  // The room is on the left.
    outer_end[i] = w.end - r.thickness_m * Perp(r.dir);
  }
  // Mitre joined neighbours (wall i ends where wall i+1 starts): the corner of
  // their outer faces, unless it lies too far out.
  for (int i = 0; i < n && n >= 2; ++i) {
    const int j = (i + 1) % n;
    if ((plan.walls[i].end - plan.walls[j].start).norm() > 1e-6) continue;
    if (walls[i].degenerate || walls[j].degenerate) continue;
    const Vec2 &da = walls[i].dir, &db = walls[j].dir;
    const double den = Cross(da, db);
    if (std::abs(den) < 1e-9) continue;
    const double s = Cross(outer_start[j] - outer_start[i], db) / den;
    const Vec2 x = outer_start[i] + s * da;
    if ((x - plan.walls[i].end).norm() <= kIfcMitreLimit * std::max(walls[i].thickness_m, walls[j].thickness_m)) {
      outer_end[i] = outer_start[j] = x;
    }
  }
  for (int i = 0; i < n; ++i) {
    ResolvedWall& r = walls[i];
    if (r.degenerate) continue;
    const Vec2 origin = plan.walls[i].start, left = Perp(r.dir);
    auto local = [&](const Vec2& p) { return Vec2((p - origin).dot(r.dir), (p - origin).dot(left)); };
    Vec2 os = local(outer_start[i]), oe = local(outer_end[i]);
    // Mitres that would cross (a wall shorter than its neighbours' thickness): square ends.
    if (!(oe.x() - os.x() > 1e-6)) os = Vec2(0, -r.thickness_m), oe = Vec2(r.length_m, -r.thickness_m);
    r.footprint = {Vec2(0, 0), os, oe, Vec2(r.length_m, 0)};
  }
  return walls;
}

// ---- The model ----

class IfcModel {
 public:
  IfcModel(const Plan& plan, const IfcOptions& options) : plan_(plan), o_(options), guid_(PlanToJson(plan).dump()) {}

  std::string Data() {
    Context();
    Spatial();
    const std::vector<ResolvedWall> walls = ResolveWalls(plan_, o_);
    std::vector<int> wall_ids, contained;
    std::vector<int> wall_placements;
    for (size_t i = 0; i < walls.size(); ++i) {
      auto [id, placement] = Wall(static_cast<int>(i), walls[i]);
      wall_ids.push_back(id);
      wall_placements.push_back(placement);
      contained.push_back(id);
    }
    int doors = 0, windows = 0;
    for (size_t i = 0; i < plan_.openings.size(); ++i) {
      const PlanOpening& op = plan_.openings[i];
      const int number = op.kind == OpeningKind::kDoor ? ++doors : ++windows;
      contained.push_back(
          Opening(static_cast<int>(i), number, walls[op.wall], wall_ids[op.wall], wall_placements[op.wall]));
    }
    double room_height_m = o_.default_wall_height_m;
    if (!walls.empty()) {
      room_height_m = 0;
      for (const ResolvedWall& w : walls) room_height_m = std::max(room_height_m, w.height_m);
    }
    std::vector<int> spaces;
    for (size_t i = 0; i < plan_.rooms.size(); ++i) spaces.push_back(Space(static_cast<int>(i), room_height_m));
    if (!spaces.empty()) Rel("IFCRELAGGREGATES", {Ref(storey_), Refs(spaces)});
    if (!contained.empty()) Rel("IFCRELCONTAINEDINSPATIALSTRUCTURE", {Refs(contained), Ref(storey_)});
    return out_.text();
  }

 private:
  // IfcRoot's first four attributes: GlobalId, OwnerHistory (none: optional
  // in IFC4), Name, Description.
  std::string Root(const std::string& name, const std::string& description = "") {
    return fmt::format("{},$,{},{}", guid_.Next(), StepString(name),
                       description.empty() ? "$" : StepString(description));
  }
  void Rel(std::string_view type, const std::vector<std::string>& args) {
    std::string text = guid_.Next() + ",$,$,$";
    for (const std::string& a : args) text += "," + a;
    out_.Add(type, text);
  }
  int Point3(double x, double y, double z) { return out_.Add("IFCCARTESIANPOINT", Reals({x, y, z})); }
  int Point2(const Vec2& p) { return out_.Add("IFCCARTESIANPOINT", Reals({p.x(), p.y()})); }
  int Placement3(double x, double y, double z, std::optional<Vec2> ref_direction = std::nullopt) {
    const int location = (x == 0 && y == 0 && z == 0) ? origin_ : Point3(x, y, z);
    std::string dir = "$";
    if (ref_direction) dir = Ref(out_.Add("IFCDIRECTION", Reals({ref_direction->x(), ref_direction->y(), 0.0})));
    return out_.Add("IFCAXIS2PLACEMENT3D",
                    fmt::format("{},{},{}", Ref(location), dir == "$" ? "$" : Ref(z_axis_), dir));
  }
  int LocalPlacement(int relative_to, int placement) {
    return out_.Add("IFCLOCALPLACEMENT", fmt::format("{},{}", relative_to ? Ref(relative_to) : "$", Ref(placement)));
  }
  int Polyline(const std::vector<Vec2>& points, bool closed) {
    std::vector<int> ids;
    for (const Vec2& p : points) ids.push_back(Point2(p));
    if (closed) ids.push_back(ids.front());
    return out_.Add("IFCPOLYLINE", Refs(ids));
  }
  // A profile extruded along +Z by depth_m, as a product's 'Body'.
  int Extrusion(int profile, double depth_m) {
    return out_.Add("IFCEXTRUDEDAREASOLID",
                    fmt::format("{},{},{},{}", Ref(profile), Ref(identity_), Ref(z_axis_), StepReal(depth_m)));
  }
  int Rectangle(double x_m, double y_m, double centre_x_m, double centre_y_m) {
    const int centre = out_.Add("IFCAXIS2PLACEMENT2D", fmt::format("{},$", Ref(Point2(Vec2(centre_x_m, centre_y_m)))));
    return out_.Add("IFCRECTANGLEPROFILEDEF",
                    fmt::format(".AREA.,$,{},{},{}", Ref(centre), StepReal(x_m), StepReal(y_m)));
  }
  int Shape(const std::vector<int>& representations) {
    return out_.Add("IFCPRODUCTDEFINITIONSHAPE", "$,$," + Refs(representations));
  }
  int BodyRep(int solid) {
    return out_.Add("IFCSHAPEREPRESENTATION", fmt::format("{},'Body','SweptSolid',({})", Ref(body_), Ref(solid)));
  }

  struct Property {
    std::string name, value, description;
  };
  static Property Length(const std::string& name, double v) {
    return {name, fmt::format("{}({})", v > 0 ? "IFCPOSITIVELENGTHMEASURE" : "IFCLENGTHMEASURE", StepReal(v)), ""};
  }
  static Property Sigma(const std::string& name, double v) {
    return {name, fmt::format("IFCLENGTHMEASURE({})", StepReal(v)), "1 sigma (standard uncertainty, 68 %)"};
  }
  static Property Flag(const std::string& name, bool v, const std::string& description) {
    return {name, v ? "IFCBOOLEAN(.T.)" : "IFCBOOLEAN(.F.)", description};
  }
  static Property Label(const std::string& name, const std::string& v, const std::string& description) {
    return {name, fmt::format("IFCLABEL({})", StepString(v)), description};
  }
  static Property Integer(const std::string& name, int v, const std::string& description) {
    return {name, fmt::format("IFCINTEGER({})", v), description};
  }
  void PropertySet(int object, const std::string& name, const std::vector<Property>& properties) {
    std::vector<int> ids;
    for (const Property& p : properties) {
      ids.push_back(out_.Add("IFCPROPERTYSINGLEVALUE",
                             fmt::format("{},{},{},$", StepString(p.name),
                                         p.description.empty() ? "$" : StepString(p.description), p.value)));
    }
    const int set = out_.Add("IFCPROPERTYSET", fmt::format("{},{}", Root(name), Refs(ids)));
    Rel("IFCRELDEFINESBYPROPERTIES", {Refs({object}), Ref(set)});
  }
  // Base quantities (IFC4 Qto_… sets): (name, entity, value).
  void Quantities(int object, const std::string& name,
                  const std::vector<std::tuple<std::string, std::string, double>>& qs) {
    std::vector<int> ids;
    for (const auto& [qname, type, value] : qs) {
      ids.push_back(out_.Add(type, fmt::format("{},$,$,{},$", StepString(qname), StepReal(value))));
    }
    const int set = out_.Add("IFCELEMENTQUANTITY", fmt::format("{},$,{}", Root(name), Refs(ids)));
    Rel("IFCRELDEFINESBYPROPERTIES", {Refs({object}), Ref(set)});
  }

  void Context() {
    origin_ = Point3(0, 0, 0);
    z_axis_ = out_.Add("IFCDIRECTION", Reals({0.0, 0.0, 1.0}));
    identity_ = out_.Add("IFCAXIS2PLACEMENT3D", fmt::format("{},$,$", Ref(origin_)));
    const int north = out_.Add("IFCDIRECTION", Reals({0.0, 1.0}));
    model_ = out_.Add("IFCGEOMETRICREPRESENTATIONCONTEXT",
                      fmt::format("$,'Model',3,1.E-05,{},{}", Ref(identity_), Ref(north)));
    body_ = out_.Add("IFCGEOMETRICREPRESENTATIONSUBCONTEXT",
                     fmt::format("'Body','Model',*,*,*,*,{},$,.MODEL_VIEW.,$", Ref(model_)));
    axis_ = out_.Add("IFCGEOMETRICREPRESENTATIONSUBCONTEXT",
                     fmt::format("'Axis','Model',*,*,*,*,{},$,.GRAPH_VIEW.,$", Ref(model_)));
    std::vector<int> units = {
        out_.Add("IFCSIUNIT", "*,.LENGTHUNIT.,$,.METRE."),
        out_.Add("IFCSIUNIT", "*,.AREAUNIT.,$,.SQUARE_METRE."),
        out_.Add("IFCSIUNIT", "*,.VOLUMEUNIT.,$,.CUBIC_METRE."),
        out_.Add("IFCSIUNIT", "*,.PLANEANGLEUNIT.,$,.RADIAN."),
    };
    units_ = out_.Add("IFCUNITASSIGNMENT", Refs(units));
  }

  void Spatial() {
    const int project =
        out_.Add("IFCPROJECT", fmt::format("{},$,$,$,({}),{}", Root(o_.project_name), Ref(model_), Ref(units_)));
    site_placement_ = LocalPlacement(0, identity_);
    const int site = out_.Add(
        "IFCSITE", fmt::format("{},$,{},$,$,.ELEMENT.,$,$,$,$,$", Root(o_.project_name), Ref(site_placement_)));
    const int building_placement = LocalPlacement(site_placement_, identity_);
    const int building = out_.Add(
        "IFCBUILDING", fmt::format("{},$,{},$,$,.ELEMENT.,$,$,$", Root(o_.project_name), Ref(building_placement)));
    storey_placement_ = LocalPlacement(building_placement, identity_);
    storey_ = out_.Add("IFCBUILDINGSTOREY",
                       fmt::format("{},$,{},$,$,.ELEMENT.,0.", Root(o_.storey_name), Ref(storey_placement_)));
    Rel("IFCRELAGGREGATES", {Ref(project), Refs({site})});
    Rel("IFCRELAGGREGATES", {Ref(site), Refs({building})});
    Rel("IFCRELAGGREGATES", {Ref(building), Refs({storey_})});
  }

  // Returns the wall's id and its placement's.
  std::pair<int, int> Wall(int index, const ResolvedWall& w) {
    const PlanWall& pw = plan_.walls[index];
    const int placement = LocalPlacement(storey_placement_, Placement3(pw.start.x(), pw.start.y(), 0.0, w.dir));
    std::string shape = "$";  // A zero-length wall has no geometry.
    if (!w.degenerate) {
      const int axis_line = Polyline({Vec2(0, 0), Vec2(w.length_m, 0)}, false);
      const int axis =
          out_.Add("IFCSHAPEREPRESENTATION", fmt::format("{},'Axis','Curve2D',({})", Ref(axis_), Ref(axis_line)));
      const int profile =
          out_.Add("IFCARBITRARYCLOSEDPROFILEDEF", fmt::format(".AREA.,$,{}", Ref(Polyline(w.footprint, true))));
      shape = Ref(Shape({axis, BodyRep(Extrusion(profile, w.height_m))}));
    }
    const int wall = out_.Add(
        "IFCWALL", fmt::format("{},$,{},{},{},.NOTDEFINED.",
                               Root(fmt::format("Wall {}", index + 1), fmt::format("plan.json walls[{}]", index)),
                               Ref(placement), shape, StepString(fmt::format("W{}", index + 1))));
    std::vector<Property> props = {Integer("PlanIndex", index, "index in plan.json walls"),
                                   Length("Length", w.length_m)};
    if (pw.length_sigma_m) props.push_back(Sigma("LengthSigma", *pw.length_sigma_m));
    if (pw.verdict)
      props.push_back(Label("Verdict", *pw.verdict, "asbuilt's verdict on this length: good, check or unreliable"));
    props.push_back(Length("Thickness", w.thickness_m));
    props.push_back(Flag("ThicknessIsDefault", w.thickness_default,
                         w.thickness_default ? "not measured: the exporter's default thickness" : "measured"));
    props.push_back(Length("Height", w.height_m));
    props.push_back(Flag("HeightIsDefault", w.height_default,
                         w.height_default ? "not measured: the exporter's default height" : "measured"));
    PropertySet(wall, "Asbuilt_Dimensions", props);
    Quantities(wall, "Qto_WallBaseQuantities",
               {{"Length", "IFCQUANTITYLENGTH", w.length_m},
                {"Width", "IFCQUANTITYLENGTH", w.thickness_m},
                {"Height", "IFCQUANTITYLENGTH", w.height_m}});
    return {wall, placement};
  }

  // The opening element voiding the wall and the door or window filling it;
  // returns the filling's id.
  int Opening(int index, int number, const ResolvedWall& w, int wall, int wall_placement) {
    const PlanOpening& op = plan_.openings[index];
    const bool door = op.kind == OpeningKind::kDoor;
    const PlanWall& pw = plan_.walls[op.wall];
    const double centre_m = (op.Centre() - pw.start).dot(w.dir);
    const double width_m = op.width;
    auto [height_m, height_default] = SizeOr(op.height, door ? o_.default_door_height_m : o_.default_window_height_m);
    double sill_m = door ? 0.0 : o_.default_window_sill_m;
    const bool sill_default = !(op.sill && *op.sill >= 0);
    if (!sill_default) sill_m = *op.sill;
    const std::string kind = door ? "Door" : "Window";
    const std::string label = fmt::format("{} {}", kind, number);
    const std::string description = fmt::format("plan.json openings[{}]", index);

    // The void: a box through the wall, from the opening's start, sill up.
    const int placement = LocalPlacement(wall_placement, Placement3(centre_m - width_m / 2, 0.0, sill_m));
    const int box =
        Extrusion(Rectangle(width_m, w.thickness_m + 2 * kOpeningMarginM, width_m / 2, -w.thickness_m / 2), height_m);
    const int opening =
        out_.Add("IFCOPENINGELEMENT", fmt::format("{},$,{},{},$,.OPENING.", Root("Opening for " + label, description),
                                                  Ref(placement), Ref(Shape({BodyRep(box)}))));
    Rel("IFCRELVOIDSELEMENT", {Ref(wall), Ref(opening)});
    Quantities(opening, "Qto_OpeningElementBaseQuantities",
               {{"Width", "IFCQUANTITYLENGTH", width_m},
                {"Height", "IFCQUANTITYLENGTH", height_m},
                {"Depth", "IFCQUANTITYLENGTH", w.thickness_m}});

    // The filling: a panel in the middle of the wall.
    const int fill_placement = LocalPlacement(placement, identity_);
    const int panel = Extrusion(
        Rectangle(width_m, std::min(kPanelThicknessM, w.thickness_m), width_m / 2, -w.thickness_m / 2), height_m);
    const std::string tag = fmt::format("{}{}", door ? "D" : "WIN", number);
    const int filling = out_.Add(door ? "IFCDOOR" : "IFCWINDOW",
                                 fmt::format("{},$,{},{},{},{},{},{},$,$", Root(label, description),
                                             Ref(fill_placement), Ref(Shape({BodyRep(panel)})), StepString(tag),
                                             StepReal(height_m), StepReal(width_m), door ? ".DOOR." : ".WINDOW."));
    Rel("IFCRELFILLSELEMENT", {Ref(opening), Ref(filling)});
    std::vector<Property> props = {Integer("PlanIndex", index, "index in plan.json openings"),
                                   Integer("PlanWallIndex", op.wall, "index in plan.json walls of the host wall"),
                                   Length("Width", width_m)};
    if (op.width_sigma_m) props.push_back(Sigma("WidthSigma", *op.width_sigma_m));
    props.push_back(Length("Height", height_m));
    if (op.height_sigma_m) props.push_back(Sigma("HeightSigma", *op.height_sigma_m));
    props.push_back(Flag("HeightIsDefault", height_default,
                         height_default ? "not measured: the exporter's default height" : "measured"));
    props.push_back({"Sill", fmt::format("IFCLENGTHMEASURE({})", StepReal(sill_m)),
                     "height of the opening's bottom above the floor"});
    if (op.sill_sigma_m) props.push_back(Sigma("SillSigma", *op.sill_sigma_m));
    props.push_back(
        Flag("SillIsDefault", sill_default, sill_default ? "not measured: the exporter's default sill" : "measured"));
    PropertySet(filling, "Asbuilt_Dimensions", props);
    Quantities(filling, door ? "Qto_DoorBaseQuantities" : "Qto_WindowBaseQuantities",
               {{"Width", "IFCQUANTITYLENGTH", width_m}, {"Height", "IFCQUANTITYLENGTH", height_m}});
    return filling;
  }

  int Space(int index, double height_m) {
    const PlanRoom& room = plan_.rooms[index];
    std::vector<Vec2> polygon = room.polygon;
    if (polygon.size() >= 2 && (polygon.front() - polygon.back()).norm() < 1e-9) polygon.pop_back();
    if (PolygonArea(polygon) < 0) std::reverse(polygon.begin(), polygon.end());
    const int placement = LocalPlacement(storey_placement_, identity_);
    std::string shape = "$";  // A room without area has no geometry.
    if (polygon.size() >= 3 && std::abs(PolygonArea(polygon)) > 1e-12) {
      const int profile =
          out_.Add("IFCARBITRARYCLOSEDPROFILEDEF", fmt::format(".AREA.,$,{}", Ref(Polyline(polygon, true))));
      shape = Ref(Shape({BodyRep(Extrusion(profile, height_m))}));
    }
    const std::string name = room.name ? *room.name : fmt::format("Room {}", index + 1);
    const int space =
        out_.Add("IFCSPACE", fmt::format("{},$,{},{},$,.ELEMENT.,.SPACE.,$",
                                         Root(name, fmt::format("plan.json rooms[{}]", index)), Ref(placement), shape));
    std::vector<Property> props = {
        Integer("PlanIndex", index, "index in plan.json rooms"),
        {"Area", fmt::format("IFCAREAMEASURE({})", StepReal(room.area_m2)), "floor area, m2"}};
    if (room.area_sigma_m2) {
      props.push_back({"AreaSigma", fmt::format("IFCAREAMEASURE({})", StepReal(*room.area_sigma_m2)),
                       "1 sigma (standard uncertainty, 68 %), m2"});
    }
    if (plan_.verdict) {
      const PlanVerdictNote& v = *plan_.verdict;
      props.push_back(Label("Verdict", v.verdict,
                            v.verdict == "good"    ? "asbuilt's verdict on this plan: good to use"
                            : v.verdict == "check" ? "asbuilt's verdict on this plan: check before use"
                                                   : "asbuilt's verdict on this plan: unreliable, not a measurement"));
      props.push_back({"Confidence", fmt::format("IFCRATIOMEASURE({})", StepReal(v.confidence)), "0 to 1"});
      for (std::size_t k = 0; k < v.reasons.size(); ++k) {
        props.push_back(
            {fmt::format("VerdictReason{}", k + 1), fmt::format("IFCTEXT({})", StepString(v.reasons[k])), ""});
      }
    }
    PropertySet(space, "Asbuilt_Dimensions", props);
    Quantities(space, "Qto_SpaceBaseQuantities",
               {{"NetFloorArea", "IFCQUANTITYAREA", room.area_m2}, {"Height", "IFCQUANTITYLENGTH", height_m}});
    return space;
  }

  const Plan& plan_;
  const IfcOptions& o_;
  GuidSource guid_;
  StepData out_;
  int origin_ = 0, z_axis_ = 0, identity_ = 0, model_ = 0, body_ = 0, axis_ = 0, units_ = 0;
  int site_placement_ = 0, storey_placement_ = 0, storey_ = 0;
};

std::string NowUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  return text;
}

std::string PlanToIfcNamed(const Plan& plan, const IfcOptions& options, const std::string& name,
                           const std::string& file_name) {
  options.Check();
  CheckModellable(plan, name);
  const std::string data = IfcModel(plan, options).Data();
  std::string out = "ISO-10303-21;\nHEADER;\n";
  out += "FILE_DESCRIPTION(('ViewDefinition [DesignTransferView_V1.0]'),'2;1');\n";
  out += fmt::format("FILE_NAME({},{},(''),(''),'asbuilt','asbuilt','');\n", StepString(file_name),
                     StepString(options.time_stamp.empty() ? NowUtc() : options.time_stamp));
  out += "FILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n";
  out += data;
  out += "ENDSEC;\nEND-ISO-10303-21;\n";
  return out;
}

}  // namespace

void IfcOptions::Check() const {
  auto positive = [](double v, const char* field) {
    CheckArgument(std::isfinite(v) && v > 0, fmt::format("IfcOptions.{} = {}, must be > 0", field, v));
  };
  positive(default_wall_thickness_m, "default_wall_thickness_m");
  positive(default_wall_height_m, "default_wall_height_m");
  positive(default_door_height_m, "default_door_height_m");
  positive(default_window_height_m, "default_window_height_m");
  CheckArgument(std::isfinite(default_window_sill_m) && default_window_sill_m >= 0,
                fmt::format("IfcOptions.default_window_sill_m = {}, must be >= 0", default_window_sill_m));
}

std::string IfcGuid(std::uint64_t high, std::uint64_t low) {
  static constexpr char kDigits[] = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$";
  std::string out(22, '0');
  // 22 digits × 6 bits = 132 bits; the first digit takes the top 2 of 128.
  for (int i = 21; i >= 0; --i) {
    out[i] = kDigits[low & 63];
    low = (low >> 6) | (high << 58);
    high >>= 6;
  }
  return out;
}

std::string PlanToIfc(const Plan& plan, const IfcOptions& options) {
  return PlanToIfcNamed(plan, options, "plan", "plan.ifc");
}

void WritePlanIfc(const Plan& plan, const std::filesystem::path& path, const IfcOptions& options) {
  WriteFileAtomic(path, PlanToIfcNamed(plan, options, path.string(), path.filename().string()));
}

}  // namespace asbuilt
