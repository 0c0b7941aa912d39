#include "asbuilt/plan/dxf.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <variant>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
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
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();        // Line ends; arc centre in a.
  double radius = 0, start_deg = 0, end_deg = 0;  // Arc.
  double height = 0.13, angle_deg = 0;            // Text.
  std::string text;
  std::vector<Vec2> points;  // Hatch / polyline.
  bool closed = true;        // Polyline.
  int anchor = 1;            // Text: 0 left, 1 centre, 2 right.
  int colour = 256;          // BYLAYER.
};

struct Dimension {
  Vec2 p1, p2;        // Measured points (extension line origins).
  Vec2 line1, line2;  // Dimension line ends.
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
      o.Code(72, e.anchor);  // Left, centred or right…
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
      o.Code(70, e.closed ? 1 : 0);
      for (const Vec2& p : e.points) {
        o.Real(10, p.x());
        o.Real(20, p.y());
      }
      break;
  }
}

Entity DxfText(const std::string& layer, const SheetText& text) {
  return {.kind = Entity::kText,
          .layer = layer,
          .a = text.at,
          .height = text.height_m,
          .angle_deg = RadToDeg(text.angle_rad),
          .text = text.text,
          .anchor = text.anchor < 0.25 ? 0 : (text.anchor > 0.75 ? 2 : 1)};
}

// The DXF entity of a model-view primitive other than a dimension: LINE (a
// two-point path), LWPOLYLINE (a longer path, or a closed one's outline),
// HATCH (a closed path's fill, grey), ARC, TEXT.
void AddDxfEntities(std::vector<Entity>& entities, const SheetPrimitive& primitive) {
  const std::string layer = SheetLayerName(primitive.layer);
  if (const auto* path = std::get_if<SheetPath>(&primitive.shape)) {
    Entity e{.layer = layer, .points = path->points};
    if (!path->closed && path->points.size() == 2) {
      e.kind = Entity::kLine;
      e.a = path->points[0];
      e.b = path->points[1];
      entities.push_back(e);
      return;
    }
    if (path->closed && path->fill) {
      e.kind = Entity::kHatch;
      e.colour = 8;
      entities.push_back(e);
    }
    if (path->stroke) {
      e.kind = Entity::kPolyline;
      e.closed = path->closed;
      e.colour = 256;
      entities.push_back(e);
    }
  } else if (const auto* arc = std::get_if<SheetArc>(&primitive.shape)) {
    entities.push_back({.kind = Entity::kArc,
                        .layer = layer,
                        .a = arc->centre,
                        .radius = arc->radius_m,
                        .start_deg = std::fmod(RadToDeg(arc->from_rad) + 360.0, 360.0),
                        .end_deg = std::fmod(RadToDeg(arc->to_rad) + 360.0, 360.0)});
  } else if (const auto* text = std::get_if<SheetText>(&primitive.shape)) {
    entities.push_back(DxfText(layer, *text));
  } else {
    throw InvalidArgument(fmt::format("SheetToDxf: the model view has dots on layer {}; the DXF draws none", layer));
  }
}

// A dimension: its rendered block (extension and dimension lines, ticks,
// text) and the DIMENSION entity's points.
Dimension MakeDxfDimension(const SheetDimension& dim, const SheetDimensionStyle& style) {
  const SheetDimensionGeometry g = DimensionGeometry(dim, style);
  Dimension d;
  d.p1 = dim.p1;
  d.p2 = dim.p2;
  d.line1 = g.line1;
  d.line2 = g.line2;
  d.text = "<>" + dim.tolerance_text;  // "<>": the measurement, in the style's units.
  d.text_at = g.text_at;
  d.text_angle_deg = RadToDeg(g.text_angle_rad);
  for (const auto& lines : {g.extension_and_dimension_lines, g.ticks}) {
    for (const auto& [a, b] : lines) {
      d.geometry.push_back({.kind = Entity::kLine, .layer = "DIMENSIONS", .a = a, .b = b});
    }
  }
  d.geometry.push_back(DxfText(
      "DIMENSIONS", {.at = g.text_at, .angle_rad = g.text_angle_rad, .height_m = style.text_height_m, .text = d.text}));
  return d;
}

// The model view: entities in list order, dimensions (numbered *D1, *D2, …)
// in list order.
struct DxfModel {
  std::vector<Entity> entities;
  std::vector<Dimension> dims;
};
DxfModel CollectDxfModel(const PlanSheet& sheet) {
  DxfModel model;
  for (const SheetPrimitive& primitive : sheet.primitives) {
    if (!InView(primitive.views, SheetView::kModel)) continue;
    CheckArgument(primitive.layer != SheetLayer::kOverlay,
                  "SheetToDxf: an OVERLAY primitive is in the model view; overlays are paper only");
    if (const auto* dim = std::get_if<SheetDimension>(&primitive.shape)) {
      model.dims.push_back(MakeDxfDimension(*dim, sheet.dimension_style));
      model.dims.back().block = fmt::format("*D{}", model.dims.size());
    } else {
      AddDxfEntities(model.entities, primitive);
    }
  }
  return model;
}

// Handles fixed up front so that tables and blocks can refer to each other.
struct DxfHandles {
  std::string vport_table, ltype_table, layer_table, style_table, view_table, ucs_table, appid_table, dimstyle_table,
      block_table, style_standard, model_record, paper_record, root_dict, group_dict;
  std::vector<std::string> dim_records;
};
DxfHandles AllocateDxfHandles(DxfOut& o, size_t dims) {
  DxfHandles h;
  for (std::string* handle : {&h.vport_table, &h.ltype_table, &h.layer_table, &h.style_table, &h.view_table,
                              &h.ucs_table, &h.appid_table, &h.dimstyle_table, &h.block_table, &h.style_standard,
                              &h.model_record, &h.paper_record, &h.root_dict, &h.group_dict}) {
    *handle = o.NewHandle();
  }
  for (size_t k = 0; k < dims; ++k) h.dim_records.push_back(o.NewHandle());
  return h;
}

// TABLES: one viewport, line types, the layers, the text and dimension
// styles (from the sheet's dimension style), and the block records.
void WriteDxfTables(DxfOut& b, const DxfHandles& h, const SheetDimensionStyle& style, const DxfModel& model) {
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
    std::string handle = b.Handle(std::string(type) == "DIMSTYLE" ? 105 : 5);
    b.Code(330, owner);
    b.Code(100, "AcDbSymbolTableRecord");
    b.Code(100, subclass);
    return handle;
  };
  table("VPORT", h.vport_table, 1);
  record("VPORT", h.vport_table, "AcDbViewportTableRecord");
  b.Code(2, "*Active");
  b.Code(70, 0);
  b.Point(10, Vec2(0, 0));
  b.Point(11, Vec2(1, 1));
  b.Real(40, 10.0);
  b.Real(41, 1.5);
  b.Code(0, "ENDTAB");

  table("LTYPE", h.ltype_table, 3);
  for (const char* name : {"ByBlock", "ByLayer", "Continuous"}) {
    record("LTYPE", h.ltype_table, "AcDbLinetypeTableRecord");
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
  std::vector<LayerDef> layers = {{"0", 7, -3},
                                  {SheetLayerName(SheetLayer::kWalls), 7, 50},
                                  {SheetLayerName(SheetLayer::kDoors), 3, 25},
                                  {SheetLayerName(SheetLayer::kWindows), 5, 25},
                                  {SheetLayerName(SheetLayer::kDimensions), 1, 13},
                                  {SheetLayerName(SheetLayer::kText), 7, 18}};
  // A verdict layer only when the plan carries that verdict (its name is the message).
  for (SheetLayer verdict : {SheetLayer::kCheck, SheetLayer::kUnreliable}) {
    const char* name = SheetLayerName(verdict);
    if (std::any_of(model.entities.begin(), model.entities.end(), [&](const Entity& e) { return e.layer == name; })) {
      layers.push_back({name, 1, 25});
    }
  }
  table("LAYER", h.layer_table, static_cast<int>(layers.size()));
  for (const LayerDef& l : layers) {
    record("LAYER", h.layer_table, "AcDbLayerTableRecord");
    b.Code(2, l.name);
    b.Code(70, 0);
    b.Code(62, l.colour);
    b.Code(6, "Continuous");
    b.Code(370, l.lineweight);
    b.Code(390, "0");
  }
  b.Code(0, "ENDTAB");

  table("STYLE", h.style_table, 1);
  b.Code(0, "STYLE");
  b.Code(5, h.style_standard);
  b.Code(330, h.style_table);
  b.Code(100, "AcDbSymbolTableRecord");
  b.Code(100, "AcDbTextStyleTableRecord");
  b.Code(2, "Standard");
  b.Code(70, 0);
  b.Real(40, 0.0);
  b.Real(41, 1.0);
  b.Real(50, 0.0);
  b.Code(71, 0);
  b.Real(42, style.text_height_m);
  b.Code(3, "txt");
  b.Code(4, "");
  b.Code(0, "ENDTAB");

  table("VIEW", h.view_table, 0);
  b.Code(0, "ENDTAB");
  table("UCS", h.ucs_table, 0);
  b.Code(0, "ENDTAB");

  table("APPID", h.appid_table, 1);
  record("APPID", h.appid_table, "AcDbRegAppTableRecord");
  b.Code(2, "ACAD");
  b.Code(70, 0);
  b.Code(0, "ENDTAB");

  table("DIMSTYLE", h.dimstyle_table, 1);
  b.Code(100, "AcDbDimStyleTable");
  record("DIMSTYLE", h.dimstyle_table, "AcDbDimStyleTableRecord");
  b.Code(2, "Standard");
  b.Code(70, 0);
  b.Real(40, 1.0);                    // DIMSCALE
  b.Real(41, style.tick_m);           // DIMASZ
  b.Real(42, style.extension_gap_m);  // DIMEXO
  b.Real(43, 0.4);                    // DIMDLI
  b.Real(44, style.overshoot_m);      // DIMEXE
  b.Real(140, style.text_height_m);   // DIMTXT
  b.Real(141, 0.0);                   // DIMCEN
  b.Real(142, style.tick_m);          // DIMTSZ: architectural ticks
  b.Real(144, 1000.0);                // DIMLFAC: show millimetres
  b.Real(147, style.text_gap_m);      // DIMGAP
  b.Code(77, 1);                      // DIMTAD: text above the line
  b.Code(78, 8);                      // DIMZIN
  b.Code(271, 0);                     // DIMDEC
  b.Code(340, h.style_standard);      // DIMTXSTY
  b.Code(0, "ENDTAB");

  table("BLOCK_RECORD", h.block_table, static_cast<int>(2 + model.dims.size()));
  auto block_record = [&](const std::string& handle, const std::string& name) {
    b.Code(0, "BLOCK_RECORD");
    b.Code(5, handle);
    b.Code(330, h.block_table);
    b.Code(100, "AcDbSymbolTableRecord");
    b.Code(100, "AcDbBlockTableRecord");
    b.Code(2, name);
  };
  block_record(h.model_record, "*Model_Space");
  block_record(h.paper_record, "*Paper_Space");
  for (size_t k = 0; k < model.dims.size(); ++k) block_record(h.dim_records[k], model.dims[k].block);
  b.Code(0, "ENDTAB");
  b.Code(0, "ENDSEC");
}

// BLOCKS: model and paper space (empty) and each dimension's rendering.
void WriteDxfBlocks(DxfOut& b, const DxfHandles& h, const DxfModel& model) {
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
  block(h.model_record, "*Model_Space", {});
  block(h.paper_record, "*Paper_Space", {});
  for (size_t k = 0; k < model.dims.size(); ++k) block(h.dim_records[k], model.dims[k].block, model.dims[k].geometry);
  b.Code(0, "ENDSEC");
}

// ENTITIES: the drawing, then the DIMENSION entities.
void WriteDxfEntities(DxfOut& b, const DxfHandles& h, const DxfModel& model) {
  b.Code(0, "SECTION");
  b.Code(2, "ENTITIES");
  for (const Entity& e : model.entities) WriteEntity(b, e, h.model_record);
  for (const Dimension& d : model.dims) {
    b.Code(0, "DIMENSION");
    b.Handle();
    b.Code(330, h.model_record);
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
}

// OBJECTS: the root dictionary with the (empty) group dictionary.
void WriteDxfObjects(DxfOut& b, const DxfHandles& h) {
  b.Code(0, "SECTION");
  b.Code(2, "OBJECTS");
  b.Code(0, "DICTIONARY");
  b.Code(5, h.root_dict);
  b.Code(330, "0");
  b.Code(100, "AcDbDictionary");
  b.Code(281, 1);
  b.Code(3, "ACAD_GROUP");
  b.Code(350, h.group_dict);
  b.Code(0, "DICTIONARY");
  b.Code(5, h.group_dict);
  b.Code(330, h.root_dict);
  b.Code(100, "AcDbDictionary");
  b.Code(281, 1);
  b.Code(0, "ENDSEC");
  b.Code(0, "EOF");
}

// HEADER (with $HANDSEED, the next free handle) and the empty CLASSES.
std::string DxfHeader(int handle_seed) {
  DxfOut header;
  header.Code(999, "asbuilt as-built floor plan (metres; dimensions shown in mm)");
  header.Code(0, "SECTION");
  header.Code(2, "HEADER");
  header.Code(9, "$ACADVER");
  header.Code(1, "AC1015");
  header.Code(9, "$HANDSEED");
  header.Code(5, fmt::format("{:X}", handle_seed));
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
  return header.text();
}

}  // namespace

std::string SheetToDxf(const PlanSheet& sheet) {
  const DxfModel model = CollectDxfModel(sheet);
  DxfOut body;
  const DxfHandles handles = AllocateDxfHandles(body, model.dims.size());
  WriteDxfTables(body, handles, sheet.dimension_style, model);
  WriteDxfBlocks(body, handles, model);
  WriteDxfEntities(body, handles, model);
  WriteDxfObjects(body, handles);
  return DxfHeader(body.next()) + body.text();
}

std::string PlanToDxf(const Plan& plan, const DrawingOptions& options) {
  return SheetToDxf(LayOutPlanSheet(plan, options));
}

void WritePlanDxf(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options) {
  options.Check();
  CheckPlanDrawable(plan, path.string());
  WriteFileAtomic(path, PlanToDxf(plan, options));
}

}  // namespace asbuilt
