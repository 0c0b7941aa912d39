#include "asbuilt/plan/dxf.h"

#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {


// Group-code writer with a handle allocator.
class DxfOut {
 public:
  void Code(int code, const std::string& value) { out_ += fmt::format("{:>3}\n{}\n", code, value); }
  void Code(int code, int value) { Code(code, std::to_string(value)); }
  void Real(int code, double value) { Code(code, fmt::format("{:.6f}", value)); }
  void Point(int code, const Vec2& p) {
    Real(code, p.x());
    Real(code + 10, p.y());
    Real(code + 20, 0.0);
  }
  std::string NewHandle() { return fmt::format("{:X}", next_++); }
  std::string Handle(int code = 5) {
    std::string h = NewHandle();
    Code(code, h);
    return h;
  }
  int next() const { return next_; }
  std::string& text() { return out_; }

 private:
  std::string out_;
  int next_ = 0x20;
};

struct Entity {
  enum Kind { kLine, kArc, kText, kHatch, kPolyline } kind = kLine;
  std::string layer;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // Line ends; arc centre in a.
  double radius = 0, start_deg = 0, end_deg = 0;  // Arc.
  double height = 0.13, angle_deg = 0;  // Text.
  std::string text;
  std::vector<Vec2> points;  // Hatch / closed polyline.
  int colour = 256;          // BYLAYER.
};

struct Dimension {
  Vec2 p1, p2;       // Measured points (extension line origins).
  Vec2 line1, line2; // Dimension line ends.
  Vec2 text_at;
  double text_angle_deg = 0;
  std::string text;
  std::string block;
  std::vector<Entity> geometry;  // Rendered into the block.
};

void WriteEntity(DxfOut& o, const Entity& e, const std::string& owner) {
  switch (e.kind) {
    case Entity::kLine:
      o.Code(0, "LINE");
      break;
    case Entity::kArc:
      o.Code(0, "ARC");
      break;
    case Entity::kText:
      o.Code(0, "TEXT");
      break;
    case Entity::kHatch:
      o.Code(0, "HATCH");
      break;
    case Entity::kPolyline:
      o.Code(0, "LWPOLYLINE");
      break;
  }
  o.Handle();
  o.Code(330, owner);
  o.Code(100, "AcDbEntity");
  o.Code(8, e.layer);
  if (e.colour != 256) o.Code(62, e.colour);
  switch (e.kind) {
    case Entity::kLine:
      o.Code(100, "AcDbLine");
      o.Point(10, e.a);
      o.Point(11, e.b);
      break;
    case Entity::kArc:
      o.Code(100, "AcDbCircle");
      o.Point(10, e.a);
      o.Real(40, e.radius);
      o.Code(100, "AcDbArc");
      o.Real(50, e.start_deg);
      o.Real(51, e.end_deg);
      break;
    case Entity::kText:
      o.Code(100, "AcDbText");
      o.Point(10, e.a);
      o.Real(40, e.height);
      o.Code(1, e.text);
      o.Real(50, e.angle_deg);
      o.Code(72, 1);  // Centred…
      o.Point(11, e.a);
      o.Code(100, "AcDbText");
      o.Code(73, 0);  // …on the baseline.
      break;
    case Entity::kHatch:
      o.Code(100, "AcDbHatch");
      o.Point(10, Vec2::Zero());
      o.Real(210, 0.0);
      o.Real(220, 0.0);
      o.Real(230, 1.0);
      o.Code(2, "SOLID");
      o.Code(70, 1);  // Solid fill.
      o.Code(71, 0);  // Not associative.
      o.Code(91, 1);  // One boundary path…
      o.Code(92, 3);  // …external polyline.
      o.Code(72, 0);
      o.Code(73, 1);
      o.Code(93, static_cast<int>(e.points.size()));
      for (const Vec2& p : e.points) {
        o.Real(10, p.x());
        o.Real(20, p.y());
      }
      o.Code(97, 0);
      o.Code(75, 0);
      o.Code(76, 1);
      o.Code(98, 0);
      break;
    case Entity::kPolyline:
      o.Code(100, "AcDbPolyline");
      o.Code(90, static_cast<int>(e.points.size()));
      o.Code(70, 1);  // Closed.
      for (const Vec2& p : e.points) {
        o.Real(10, p.x());
        o.Real(20, p.y());
      }
      break;
  }
}

Entity Line(const std::string& layer, const Vec2& a, const Vec2& b) {
  Entity e;
  e.kind = Entity::kLine;
  e.layer = layer;
  e.a = a;
  e.b = b;
  return e;
}

Dimension MakeDimension(const Vec2& a, const Vec2& b, const Vec2& out, double offset, const std::string& text,
                        const DrawingOptions& opt) {
  Dimension d;
  d.p1 = a;
  d.p2 = b;
  d.line1 = a + offset * out;
  d.line2 = b + offset * out;
  d.text = text;
  Vec2 dir = (b - a).normalized();
  double angle = ReadableTextAngle(std::atan2(dir.y(), dir.x()));
  Vec2 up = Perp(Vec2(std::cos(angle), std::sin(angle)));
  d.text_at = 0.5 * (d.line1 + d.line2) + 0.04 * up;
  d.text_angle_deg = RadToDeg(angle);
  // Block geometry: extension lines, dimension line, ticks, text.
  const double gap = 0.05, over = 0.08, tick = 0.07;
  d.geometry.push_back(Line("DIMENSIONS", a + gap * out, d.line1 + over * out));
  d.geometry.push_back(Line("DIMENSIONS", b + gap * out, d.line2 + over * out));
  d.geometry.push_back(Line("DIMENSIONS", d.line1 - over * dir, d.line2 + over * dir));
  Vec2 slash = (dir + out).normalized() * tick;
  d.geometry.push_back(Line("DIMENSIONS", d.line1 - slash, d.line1 + slash));
  d.geometry.push_back(Line("DIMENSIONS", d.line2 - slash, d.line2 + slash));
  Entity t;
  t.kind = Entity::kText;
  t.layer = "DIMENSIONS";
  t.a = d.text_at;
  t.height = opt.text_height_m;
  t.angle_deg = d.text_angle_deg;
  t.text = text;
  d.geometry.push_back(t);
  return d;
}


}  // namespace

std::string PlanToDxf(const Plan& plan, const DrawingOptions& opt) {
  opt.Check();
  std::vector<Entity> entities;
  std::vector<Dimension> dims;
  const int n = static_cast<int>(plan.walls.size());
  auto outward = [&](int i) -> Vec2 { return -Perp((plan.walls[i].end - plan.walls[i].start).normalized()); };

  // Walls: the measured inner face, and each piece between openings.
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    double len = w.Length();
    if (len <= 0) continue;
    Vec2 d = (w.end - w.start) / len, out = outward(i);
    double th = DrawnThickness(w, opt);
    entities.push_back(Line("WALLS", w.start, w.end));
    for (auto [t0, t1] : WallPiecesBetweenOpenings(plan, i)) {
      Vec2 i0 = w.start + t0 * d, i1 = w.start + t1 * d;
      Entity hatch;
      hatch.kind = Entity::kHatch;
      hatch.layer = "WALLS";
      hatch.colour = 8;
      hatch.points = {i0, i1, i1 + th * out, i0 + th * out};
      entities.push_back(hatch);
      Entity outline = hatch;
      outline.kind = Entity::kPolyline;
      outline.colour = 256;
      entities.push_back(outline);
    }
    // Dimension of the inner length.
    std::string text = "<>";
    std::string sigma_text = DimensionText(len, w.length_sigma_m, opt);
    if (auto pm = sigma_text.find(" ±"); pm != std::string::npos) text += sigma_text.substr(pm);
    dims.push_back(MakeDimension(w.start, w.end, out, th + 0.85, text, opt));
  }
  // Openings.
  for (const PlanOpening& op : plan.openings) {
    const PlanWall& w = plan.walls[op.wall];
    Vec2 d = (w.end - w.start).normalized(), out = outward(op.wall), in = -out;
    double th = DrawnThickness(w, opt);
    Vec2 a = op.start, b = op.end;
    if (d.dot(b - a) < 0) std::swap(a, b);
    const std::string layer = op.kind == OpeningKind::kDoor ? "DOORS" : "WINDOWS";
    entities.push_back(Line(layer, a, a + th * out));
    entities.push_back(Line(layer, b, b + th * out));
    double width = (b - a).norm();
    if (op.kind == OpeningKind::kDoor) {
      entities.push_back(Line(layer, a, a + width * in));
      Entity arc;
      arc.kind = Entity::kArc;
      arc.layer = layer;
      arc.a = a;
      arc.radius = width;
      double from = RadToDeg(std::atan2(d.y(), d.x())), to = RadToDeg(std::atan2(in.y(), in.x()));
      if (std::fmod(to - from + 720.0, 360.0) > 180.0) std::swap(from, to);
      arc.start_deg = std::fmod(from + 360.0, 360.0);
      arc.end_deg = std::fmod(to + 360.0, 360.0);
      entities.push_back(arc);
    } else {
      entities.push_back(Line(layer, a, b));
      entities.push_back(Line(layer, a + th * out, b + th * out));
      entities.push_back(Line(layer, a + (0.5 * th - 0.015) * out, b + (0.5 * th - 0.015) * out));
      entities.push_back(Line(layer, a + (0.5 * th + 0.015) * out, b + (0.5 * th + 0.015) * out));
    }
    std::string text = "<>";
    std::string sigma_text = DimensionText(width, op.width_sigma_m, opt);
    if (auto pm = sigma_text.find(" ±"); pm != std::string::npos) text += sigma_text.substr(pm);
    dims.push_back(MakeDimension(a, b, out, th + 0.4, text, opt));
  }
  // Room area and title.
  for (const PlanRoom& room : plan.rooms) {
    if (room.polygon.size() < 3) continue;
    Vec2 c = Vec2::Zero();
    double a2 = 0;
    for (size_t k = 0; k < room.polygon.size(); ++k) {
      const Vec2& p = room.polygon[k];
      const Vec2& q = room.polygon[(k + 1) % room.polygon.size()];
      double cr = p.x() * q.y() - p.y() * q.x();
      a2 += cr;
      c += cr * (p + q);
    }
    c /= 3 * a2;
    Entity t;
    t.kind = Entity::kText;
    t.layer = "TEXT";
    t.a = c;
    t.height = 1.2 * opt.text_height_m;
    t.text = fmt::format("{:.2f} m2", room.area_m2);
    if (opt.show_uncertainty && room.area_sigma_m2) {
      t.text = fmt::format("{:.2f} +/- {:.2f} m2", room.area_m2, std::max(0.01, *room.area_sigma_m2));
    }
    entities.push_back(t);
  }

  // Assign blocks to dimensions.
  for (size_t k = 0; k < dims.size(); ++k) dims[k].block = fmt::format("*D{}", k + 1);

  DxfOut o;
  // Handles fixed up front so tables and blocks can refer to each other.
  const std::string h_vport_table = o.NewHandle(), h_ltype_table = o.NewHandle(), h_layer_table = o.NewHandle(),
                    h_style_table = o.NewHandle(), h_view_table = o.NewHandle(), h_ucs_table = o.NewHandle(),
                    h_appid_table = o.NewHandle(), h_dimstyle_table = o.NewHandle(),
                    h_block_table = o.NewHandle(), h_style_standard = o.NewHandle(),
                    h_model_record = o.NewHandle(), h_paper_record = o.NewHandle(), h_root_dict = o.NewHandle(),
                    h_group_dict = o.NewHandle();
  std::vector<std::string> dim_records;
  for (size_t k = 0; k < dims.size(); ++k) dim_records.push_back(o.NewHandle());

  std::string body;
  DxfOut& b = o;
  // Everything below is appended in order; the header (with $HANDSEED) is
  // prepended at the end once all handles are known.

  // TABLES.
  b.Code(0, "SECTION");
  b.Code(2, "TABLES");
  auto table = [&](const char* name, const std::string& handle, int count) {
    b.Code(0, "TABLE");
    b.Code(2, name);
    b.Code(5, handle);
    b.Code(330, "0");
    b.Code(100, "AcDbSymbolTable");
    b.Code(70, count);
  };
  auto record = [&](const char* type, const std::string& owner, const char* subclass) {
    b.Code(0, type);
    std::string h = b.Handle(std::string(type) == "DIMSTYLE" ? 105 : 5);
    b.Code(330, owner);
    b.Code(100, "AcDbSymbolTableRecord");
    b.Code(100, subclass);
    return h;
  };
  table("VPORT", h_vport_table, 1);
  record("VPORT", h_vport_table, "AcDbViewportTableRecord");
  b.Code(2, "*Active");
  b.Code(70, 0);
  b.Point(10, Vec2(0, 0));
  b.Point(11, Vec2(1, 1));
  b.Real(40, 10.0);
  b.Real(41, 1.5);
  b.Code(0, "ENDTAB");

  table("LTYPE", h_ltype_table, 3);
  for (const char* name : {"ByBlock", "ByLayer", "Continuous"}) {
    record("LTYPE", h_ltype_table, "AcDbLinetypeTableRecord");
    b.Code(2, name);
    b.Code(70, 0);
    b.Code(3, std::string(name) == "Continuous" ? "Solid line" : "");
    b.Code(72, 65);
    b.Code(73, 0);
    b.Real(40, 0.0);
  }
  b.Code(0, "ENDTAB");

  struct LayerDef {
    const char* name;
    int colour;
    int lineweight;  // 1/100 mm.
  };
  const LayerDef layers[] = {{"0", 7, -3},         {"WALLS", 7, 50},   {"DOORS", 3, 25},
                             {"WINDOWS", 5, 25},   {"DIMENSIONS", 1, 13}, {"TEXT", 7, 18}};
  table("LAYER", h_layer_table, static_cast<int>(std::size(layers)));
  for (const LayerDef& l : layers) {
    record("LAYER", h_layer_table, "AcDbLayerTableRecord");
    b.Code(2, l.name);
    b.Code(70, 0);
    b.Code(62, l.colour);
    b.Code(6, "Continuous");
    b.Code(370, l.lineweight);
    b.Code(390, "0");
  }
  b.Code(0, "ENDTAB");

  table("STYLE", h_style_table, 1);
  b.Code(0, "STYLE");
  b.Code(5, h_style_standard);
  b.Code(330, h_style_table);
  b.Code(100, "AcDbSymbolTableRecord");
  b.Code(100, "AcDbTextStyleTableRecord");
  b.Code(2, "Standard");
  b.Code(70, 0);
  b.Real(40, 0.0);
  b.Real(41, 1.0);
  b.Real(50, 0.0);
  b.Code(71, 0);
  b.Real(42, opt.text_height_m);
  b.Code(3, "txt");
  b.Code(4, "");
  b.Code(0, "ENDTAB");

  table("VIEW", h_view_table, 0);
  b.Code(0, "ENDTAB");
  table("UCS", h_ucs_table, 0);
  b.Code(0, "ENDTAB");

  table("APPID", h_appid_table, 1);
  record("APPID", h_appid_table, "AcDbRegAppTableRecord");
  b.Code(2, "ACAD");
  b.Code(70, 0);
  b.Code(0, "ENDTAB");

  table("DIMSTYLE", h_dimstyle_table, 1);
  b.Code(100, "AcDbDimStyleTable");
  record("DIMSTYLE", h_dimstyle_table, "AcDbDimStyleTableRecord");
  b.Code(2, "Standard");
  b.Code(70, 0);
  b.Real(40, 1.0);                 // DIMSCALE
  b.Real(41, 0.07);                // DIMASZ
  b.Real(42, 0.05);                // DIMEXO
  b.Real(43, 0.4);                 // DIMDLI
  b.Real(44, 0.08);                // DIMEXE
  b.Real(140, opt.text_height_m);  // DIMTXT
  b.Real(141, 0.0);                // DIMCEN
  b.Real(142, 0.07);               // DIMTSZ: architectural ticks
  b.Real(144, 1000.0);             // DIMLFAC: show millimetres
  b.Real(147, 0.04);               // DIMGAP
  b.Code(77, 1);                   // DIMTAD: text above the line
  b.Code(78, 8);                   // DIMZIN
  b.Code(271, 0);                  // DIMDEC
  b.Code(340, h_style_standard);   // DIMTXSTY
  b.Code(0, "ENDTAB");

  table("BLOCK_RECORD", h_block_table, static_cast<int>(2 + dims.size()));
  auto block_record = [&](const std::string& handle, const std::string& name) {
    b.Code(0, "BLOCK_RECORD");
    b.Code(5, handle);
    b.Code(330, h_block_table);
    b.Code(100, "AcDbSymbolTableRecord");
    b.Code(100, "AcDbBlockTableRecord");
    b.Code(2, name);
  };
  block_record(h_model_record, "*Model_Space");
  block_record(h_paper_record, "*Paper_Space");
  for (size_t k = 0; k < dims.size(); ++k) block_record(dim_records[k], dims[k].block);
  b.Code(0, "ENDTAB");
  b.Code(0, "ENDSEC");

  // BLOCKS.
  b.Code(0, "SECTION");
  b.Code(2, "BLOCKS");
  auto block = [&](const std::string& record_handle, const std::string& name, const std::vector<Entity>& content) {
    b.Code(0, "BLOCK");
    b.Handle();
    b.Code(330, record_handle);
    b.Code(100, "AcDbEntity");
    b.Code(8, "0");
    b.Code(100, "AcDbBlockBegin");
    b.Code(2, name);
    b.Code(70, name.rfind("*D", 0) == 0 ? 1 : 0);  // Anonymous for dimension blocks.
    b.Point(10, Vec2::Zero());
    b.Code(3, name);
    b.Code(1, "");
    for (const Entity& e : content) WriteEntity(b, e, record_handle);
    b.Code(0, "ENDBLK");
    b.Handle();
    b.Code(330, record_handle);
    b.Code(100, "AcDbEntity");
    b.Code(8, "0");
    b.Code(100, "AcDbBlockEnd");
  };
  block(h_model_record, "*Model_Space", {});
  block(h_paper_record, "*Paper_Space", {});
  for (size_t k = 0; k < dims.size(); ++k) block(dim_records[k], dims[k].block, dims[k].geometry);
  b.Code(0, "ENDSEC");

  // ENTITIES.
  b.Code(0, "SECTION");
  b.Code(2, "ENTITIES");
  for (const Entity& e : entities) WriteEntity(b, e, h_model_record);
  for (const Dimension& d : dims) {
    b.Code(0, "DIMENSION");
    b.Handle();
    b.Code(330, h_model_record);
    b.Code(100, "AcDbEntity");
    b.Code(8, "DIMENSIONS");
    b.Code(100, "AcDbDimension");
    b.Code(2, d.block);
    b.Point(10, d.line2);
    b.Point(11, d.text_at);
    // A rotated (linear) dimension along the measured direction: the same
    // as an aligned one here, and read back right by every reader (ezdxf
    // measures aligned dimensions along the x axis).
    b.Code(70, 0 | 32);  // Linear, block referenced by this dimension only.
    b.Code(71, 5);       // Text attachment: bottom centre.
    b.Code(1, d.text);
    b.Real(53, d.text_angle_deg);
    b.Code(3, "Standard");
    b.Code(100, "AcDbAlignedDimension");
    b.Point(13, d.p1);
    b.Point(14, d.p2);
    Vec2 dir = d.p2 - d.p1;
    b.Real(50, RadToDeg(std::atan2(dir.y(), dir.x())));
    b.Code(100, "AcDbRotatedDimension");
  }
  b.Code(0, "ENDSEC");

  // OBJECTS: the root dictionary with the (empty) group dictionary.
  b.Code(0, "SECTION");
  b.Code(2, "OBJECTS");
  b.Code(0, "DICTIONARY");
  b.Code(5, h_root_dict);
  b.Code(330, "0");
  b.Code(100, "AcDbDictionary");
  b.Code(281, 1);
  b.Code(3, "ACAD_GROUP");
  b.Code(350, h_group_dict);
  b.Code(0, "DICTIONARY");
  b.Code(5, h_group_dict);
  b.Code(330, h_root_dict);
  b.Code(100, "AcDbDictionary");
  b.Code(281, 1);
  b.Code(0, "ENDSEC");
  b.Code(0, "EOF");

  body = std::move(b.text());
  DxfOut header;
  header.Code(999, "asbuilt as-built floor plan (metres; dimensions shown in mm)");
  header.Code(0, "SECTION");
  header.Code(2, "HEADER");
  header.Code(9, "$ACADVER");
  header.Code(1, "AC1015");
  header.Code(9, "$HANDSEED");
  header.Code(5, fmt::format("{:X}", o.next()));
  header.Code(9, "$INSUNITS");
  header.Code(70, 6);  // Metres.
  header.Code(9, "$MEASUREMENT");
  header.Code(70, 1);  // Metric.
  header.Code(9, "$LUNITS");
  header.Code(70, 2);
  header.Code(9, "$DIMSTYLE");
  header.Code(2, "Standard");
  header.Code(9, "$TEXTSTYLE");
  header.Code(7, "Standard");
  header.Code(9, "$CLAYER");
  header.Code(8, "0");
  header.Code(0, "ENDSEC");
  header.Code(0, "SECTION");
  header.Code(2, "CLASSES");
  header.Code(0, "ENDSEC");
  return header.text() + body;
}

void WritePlanDxf(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options) {
  WriteFileAtomic(path, PlanToDxf(plan, options));
}

}  // namespace asbuilt
