// ifc_check PLAN.ifc PLAN.json — reads an IFC file back with an independent
// reader (IFC++, Debian's libifcplusplus) and checks it against the plan it
// was written from: the spatial tree project → site → building → storey,
// metres, and every wall, opening and space — positions composed from the
// IfcLocalPlacement chain, sizes from the geometry (axis polyline, extruded
// profiles), the quantity sets, IfcDoor/IfcWindow overall sizes, the
// void/fill relations and the Asbuilt_Dimensions property set. Prints
// "ok: 4 walls, 1 door, 2 windows, 1 space; max difference 0.000 mm" and
// exits 0, or lists every problem and exits 1 (2: unreadable).
//
// Built with the tests (plan_test runs it, as dxf_check.py for plan.dxf);
// `build/src/asbuilt/plan/ifc_check out/plan.ifc out/plan.json` checks any
// survey's output.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ifcpp/IFC4/include/IfcArbitraryClosedProfileDef.h>
#include <ifcpp/IFC4/include/IfcAreaMeasure.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement3D.h>
#include <ifcpp/IFC4/include/IfcBoolean.h>
#include <ifcpp/IFC4/include/IfcBuilding.h>
#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcCartesianPoint.h>
#include <ifcpp/IFC4/include/IfcDirection.h>
#include <ifcpp/IFC4/include/IfcDoor.h>
#include <ifcpp/IFC4/include/IfcElementQuantity.h>
#include <ifcpp/IFC4/include/IfcExtrudedAreaSolid.h>
#include <ifcpp/IFC4/include/IfcIdentifier.h>
#include <ifcpp/IFC4/include/IfcInteger.h>
#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcLocalPlacement.h>
#include <ifcpp/IFC4/include/IfcOpeningElement.h>
#include <ifcpp/IFC4/include/IfcPolyline.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcProductDefinitionShape.h>
#include <ifcpp/IFC4/include/IfcProject.h>
#include <ifcpp/IFC4/include/IfcPropertySet.h>
#include <ifcpp/IFC4/include/IfcPropertySingleValue.h>
#include <ifcpp/IFC4/include/IfcQuantityArea.h>
#include <ifcpp/IFC4/include/IfcQuantityLength.h>
#include <ifcpp/IFC4/include/IfcReal.h>
#include <ifcpp/IFC4/include/IfcRectangleProfileDef.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/IFC4/include/IfcRelDefinesByProperties.h>
#include <ifcpp/IFC4/include/IfcRelFillsElement.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcSIPrefix.h>
#include <ifcpp/IFC4/include/IfcSIUnit.h>
#include <ifcpp/IFC4/include/IfcSIUnitName.h>
#include <ifcpp/IFC4/include/IfcShapeRepresentation.h>
#include <ifcpp/IFC4/include/IfcSite.h>
#include <ifcpp/IFC4/include/IfcSpace.h>
#include <ifcpp/IFC4/include/IfcUnitAssignment.h>
#include <ifcpp/IFC4/include/IfcUnitEnum.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/IFC4/include/IfcWindow.h>
#include <ifcpp/model/BuildingModel.h>
#include <ifcpp/reader/ReaderSTEP.h>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

// Differences beyond this (metres, m²) are problems: the writer keeps every
// digit, so a correct file agrees to rounding.
constexpr double kTolerance = 1e-6;

std::string Narrow(const std::wstring& w) {
  std::string s;
  for (wchar_t c : w) s += c < 128 ? static_cast<char>(c) : '?';
  return s;
}

class Checker {
 public:
  Checker(const Plan& plan, shared_ptr<BuildingModel> model) : plan_(plan), model_(std::move(model)) {
    for (const auto& [id, e] : model_->getMapIfcEntities()) entities_.push_back(e);
  }

  int Run() {
    CheckSpatialTree();
    CheckUnits();
    CollectRelations();
    CheckWalls();
    CheckOpenings();
    CheckSpaces();
    if (!problems_.empty()) {
      for (const std::string& p : problems_) std::printf("problem: %s\n", p.c_str());
      return 1;
    }
    std::printf("ok: %d walls, %d door%s, %d window%s, %d space%s; max difference %.3f mm\n", walls_, doors_,
                doors_ == 1 ? "" : "s", windows_, windows_ == 1 ? "" : "s", spaces_, spaces_ == 1 ? "" : "s",
                max_difference_ * 1000);
    return 0;
  }

 private:
  template <typename T>
  std::vector<shared_ptr<T>> All() const {
    std::vector<shared_ptr<T>> out;
    for (const auto& e : entities_) {
      if (auto t = std::dynamic_pointer_cast<T>(e)) out.push_back(t);
    }
    return out;
  }
  void Problem(const std::string& text) { problems_.push_back(text); }
  void Compare(const std::string& what, double read, double expected) {
    const double d = std::abs(read - expected);
    if (std::isfinite(d)) max_difference_ = std::max(max_difference_, d);
    if (!(d <= kTolerance))
      Problem(what + ": read " + std::to_string(read) + ", plan.json " + std::to_string(expected));
  }

  // ---- geometry ----
  static Vector3d Point(const shared_ptr<IfcCartesianPoint>& p) {
    Vector3d v = Vector3d::Zero();
    for (size_t i = 0; p && i < p->m_Coordinates.size() && i < 3; ++i) v[i] = p->m_Coordinates[i]->m_value;
    return v;
  }
  static Vector3d Direction(const shared_ptr<IfcDirection>& d, const Vector3d& fallback) {
    if (!d) return fallback;
    Vector3d v = Vector3d::Zero();
    for (size_t i = 0; i < d->m_DirectionRatios.size() && i < 3; ++i) v[i] = d->m_DirectionRatios[i]->m_value;
    return v.normalized();
  }
  static Isometry3d Transform(const shared_ptr<IfcAxis2Placement3D>& a) {
    Isometry3d t = Isometry3d::Identity();
    if (!a) return t;
    const Vector3d z = Direction(a->m_Axis, Vector3d::UnitZ());
    Vector3d x = Direction(a->m_RefDirection, Vector3d::UnitX());
    x = (x - x.dot(z) * z).normalized();
    t.linear().col(0) = x;
    t.linear().col(1) = z.cross(x);
    t.linear().col(2) = z;
    t.translation() = Point(a->m_Location);
    return t;
  }
  // The placement chain up to the world.
  Isometry3d World(const shared_ptr<IfcObjectPlacement>& placement) {
    auto local = std::dynamic_pointer_cast<IfcLocalPlacement>(placement);
    if (!local) return Isometry3d::Identity();
    Isometry3d relative = Transform(std::dynamic_pointer_cast<IfcAxis2Placement3D>(local->m_RelativePlacement));
    return World(local->m_PlacementRelTo) * relative;
  }
  static shared_ptr<IfcShapeRepresentation> Representation(const shared_ptr<IfcProduct>& p, const std::wstring& id) {
    if (!p->m_Representation) return nullptr;
    for (const auto& r : p->m_Representation->m_Representations) {
      auto s = std::dynamic_pointer_cast<IfcShapeRepresentation>(r);
      if (s && s->m_RepresentationIdentifier && s->m_RepresentationIdentifier->m_value == id) return s;
    }
    return nullptr;
  }
  static shared_ptr<IfcExtrudedAreaSolid> Body(const shared_ptr<IfcProduct>& p) {
    auto rep = Representation(p, L"Body");
    if (!rep || rep->m_Items.size() != 1) return nullptr;
    return std::dynamic_pointer_cast<IfcExtrudedAreaSolid>(rep->m_Items[0]);
  }
  static std::vector<Vector3d> PolylinePoints(const shared_ptr<IfcCurve>& curve) {
    std::vector<Vector3d> out;
    if (auto line = std::dynamic_pointer_cast<IfcPolyline>(curve)) {
      for (const auto& p : line->m_Points) out.push_back(Point(p));
    }
    return out;
  }

  // ---- property and quantity sets ----
  struct Sets {
    std::map<std::string, shared_ptr<IfcValue>> properties;  // Asbuilt_Dimensions.
    std::map<std::string, double> quantities;                // Qto_….
    std::string qto_name;
  };
  void CollectRelations() {
    for (const auto& rel : All<IfcRelDefinesByProperties>()) {
      for (const auto& object : rel->m_RelatedObjects) {
        Sets& sets = sets_[object.get()];
        if (auto pset = std::dynamic_pointer_cast<IfcPropertySet>(rel->m_RelatingPropertyDefinition)) {
          if (!pset->m_Name || pset->m_Name->m_value != L"Asbuilt_Dimensions") continue;
          for (const auto& p : pset->m_HasProperties) {
            auto single = std::dynamic_pointer_cast<IfcPropertySingleValue>(p);
            if (single && single->m_Name) sets.properties[Narrow(single->m_Name->m_value)] = single->m_NominalValue;
          }
        } else if (auto qto = std::dynamic_pointer_cast<IfcElementQuantity>(rel->m_RelatingPropertyDefinition)) {
          if (qto->m_Name) sets.qto_name = Narrow(qto->m_Name->m_value);
          for (const auto& q : qto->m_Quantities) {
            if (auto l = std::dynamic_pointer_cast<IfcQuantityLength>(q)) {
              sets.quantities[Narrow(l->m_Name->m_value)] = l->m_LengthValue->m_value;
            } else if (auto a = std::dynamic_pointer_cast<IfcQuantityArea>(q)) {
              sets.quantities[Narrow(a->m_Name->m_value)] = a->m_AreaValue->m_value;
            }
          }
        }
      }
    }
    for (const auto& rel : All<IfcRelContainedInSpatialStructure>()) {
      for (const auto& e : rel->m_RelatedElements) container_[e.get()] = rel->m_RelatingStructure.get();
    }
    for (const auto& rel : All<IfcRelAggregates>()) {
      for (const auto& e : rel->m_RelatedObjects) parent_[e.get()] = rel->m_RelatingObject.get();
    }
  }
  std::optional<double> Number(const Sets& s, const std::string& name) const {
    auto it = s.properties.find(name);
    if (it == s.properties.end() || !it->second) return std::nullopt;
    if (auto v = std::dynamic_pointer_cast<IfcPositiveLengthMeasure>(it->second)) return v->m_value;
    if (auto v = std::dynamic_pointer_cast<IfcLengthMeasure>(it->second)) return v->m_value;
    if (auto v = std::dynamic_pointer_cast<IfcAreaMeasure>(it->second)) return v->m_value;
    if (auto v = std::dynamic_pointer_cast<IfcInteger>(it->second)) return v->m_value;
    return std::nullopt;
  }
  std::optional<bool> Boolean(const Sets& s, const std::string& name) const {
    auto it = s.properties.find(name);
    if (it == s.properties.end()) return std::nullopt;
    if (auto v = std::dynamic_pointer_cast<IfcBoolean>(it->second)) return v->m_value;
    return std::nullopt;
  }
  // A property that must equal the plan's optional value (absent when the plan has none).
  void CompareOptional(const std::string& what, const Sets& s, const std::string& name,
                       const std::optional<double>& expected) {
    std::optional<double> read = Number(s, name);
    if (read.has_value() != expected.has_value()) {
      Problem(what + ": " + name + (read ? " present" : " missing") + " but " + (expected ? "given" : "absent") +
              " in plan.json");
    } else if (read) {
      Compare(what + " " + name, *read, *expected);
    }
  }
  // The plan.json index an object carries.
  int Index(const void* object, const std::string& what) {
    std::optional<double> i = Number(sets_[object], "PlanIndex");
    if (!i) {
      Problem(what + " has no Asbuilt_Dimensions.PlanIndex");
      return -1;
    }
    return static_cast<int>(*i);
  }

  // ---- checks ----
  void CheckSpatialTree() {
    auto projects = All<IfcProject>();
    auto sites = All<IfcSite>();
    auto buildings = All<IfcBuilding>();
    auto storeys = All<IfcBuildingStorey>();
    if (projects.size() != 1 || sites.size() != 1 || buildings.size() != 1 || storeys.size() != 1) {
      Problem("expected one project, site, building and storey; read " + std::to_string(projects.size()) + ", " +
              std::to_string(sites.size()) + ", " + std::to_string(buildings.size()) + ", " +
              std::to_string(storeys.size()));
      return;
    }
    project_ = projects[0].get();
    site_ = sites[0].get();
    building_ = buildings[0].get();
    storey_ = storeys[0].get();
  }
  void CheckSpatialParents() {
    if (parent_[site_] != project_) Problem("the site is not aggregated into the project");
    if (parent_[building_] != site_) Problem("the building is not aggregated into the site");
    if (parent_[storey_] != building_) Problem("the storey is not aggregated into the building");
  }
  void CheckUnits() {
    auto projects = All<IfcProject>();
    bool metre = false;
    if (!projects.empty() && projects[0]->m_UnitsInContext) {
      for (const auto& u : projects[0]->m_UnitsInContext->m_Units) {
        auto si = std::dynamic_pointer_cast<IfcSIUnit>(u);
        if (si && si->m_UnitType && si->m_UnitType->m_enum == IfcUnitEnum::ENUM_LENGTHUNIT) {
          metre = si->m_Name && si->m_Name->m_enum == IfcSIUnitName::ENUM_METRE && !si->m_Prefix;
        }
      }
    }
    if (!metre) Problem("the project's length unit is not the metre");
  }

  void CheckWalls() {
    CheckSpatialParents();
    auto walls = All<IfcWall>();
    walls_ = static_cast<int>(walls.size());
    if (walls.size() != plan_.walls.size()) {
      Problem("read " + std::to_string(walls.size()) + " walls, plan.json has " + std::to_string(plan_.walls.size()));
    }
    for (const auto& wall : walls) {
      const int i = Index(wall.get(), "a wall");
      if (i < 0 || i >= static_cast<int>(plan_.walls.size())) continue;
      const std::string what = "walls[" + std::to_string(i) + "]";
      const PlanWall& pw = plan_.walls[i];
      wall_by_index_[i] = wall.get();
      if (container_[wall.get()] != storey_) Problem(what + " is not contained in the storey");
      const Isometry3d world = World(wall->m_ObjectPlacement);
      // Axis: the inner face line, from the wall's start to its end.
      auto axis = Representation(wall, L"Axis");
      std::vector<Vector3d> line = axis && axis->m_Items.size() == 1
                                       ? PolylinePoints(std::dynamic_pointer_cast<IfcCurve>(axis->m_Items[0]))
                                       : std::vector<Vector3d>{};
      if (line.size() != 2) {
        Problem(what + ": no 'Axis' polyline of two points");
      } else {
        const Vector3d a = world * line[0], b = world * line[1];
        Compare(what + " start x", a.x(), pw.start.x());
        Compare(what + " start y", a.y(), pw.start.y());
        Compare(what + " end x", b.x(), pw.end.x());
        Compare(what + " end y", b.y(), pw.end.y());
        Compare(what + " start z", a.z(), 0.0);
      }
      // Body: the footprint between the inner face (y = 0) and the outer one
      // (y = −thickness), extruded up by the height.
      auto body = Body(wall);
      const Sets& sets = sets_[wall.get()];
      const double thickness = Number(sets, "Thickness").value_or(NAN);
      const double height = Number(sets, "Height").value_or(NAN);
      if (!body) {
        Problem(what + ": no extruded 'Body'");
      } else {
        auto profile = std::dynamic_pointer_cast<IfcArbitraryClosedProfileDef>(body->m_SweptArea);
        std::vector<Vector3d> pts = profile ? PolylinePoints(profile->m_OuterCurve) : std::vector<Vector3d>{};
        double lo = INFINITY, hi = -INFINITY;
        for (const Vector3d& p : pts) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
        Compare(what + " body inner face", hi, 0.0);
        Compare(what + " body thickness", hi - lo, thickness);
        Compare(what + " body height", body->m_Depth->m_value, height);
      }
      if (pw.thickness && *pw.thickness > 0) Compare(what + " thickness", thickness, *pw.thickness);
      if (Boolean(sets, "ThicknessIsDefault") != std::optional<bool>(!(pw.thickness && *pw.thickness > 0))) {
        Problem(what + ": ThicknessIsDefault does not say whether plan.json gives the thickness");
      }
      if (pw.height && *pw.height > 0) Compare(what + " height", height, *pw.height);
      if (Boolean(sets, "HeightIsDefault") != std::optional<bool>(!(pw.height && *pw.height > 0))) {
        Problem(what + ": HeightIsDefault does not say whether plan.json gives the height");
      }
      Compare(what + " Length", Number(sets, "Length").value_or(NAN), pw.Length());
      CompareOptional(what, sets, "LengthSigma", pw.length_sigma_m);
      if (sets.qto_name != "Qto_WallBaseQuantities") Problem(what + ": no Qto_WallBaseQuantities");
      Compare(what + " Qto Length", sets.quantities.count("Length") ? sets.quantities.at("Length") : NAN, pw.Length());
      Compare(what + " Qto Width", sets.quantities.count("Width") ? sets.quantities.at("Width") : NAN, thickness);
      Compare(what + " Qto Height", sets.quantities.count("Height") ? sets.quantities.at("Height") : NAN, height);
    }
  }

  void CheckOpenings() {
    std::map<const void*, const void*> voided, filling;  // opening → wall, opening → door/window
    for (const auto& rel : All<IfcRelVoidsElement>()) {
      if (voided.count(rel->m_RelatedOpeningElement.get())) Problem("an opening voids two walls");
      voided[rel->m_RelatedOpeningElement.get()] = rel->m_RelatingBuildingElement.get();
    }
    for (const auto& rel : All<IfcRelFillsElement>()) {
      if (filling.count(rel->m_RelatingOpeningElement.get())) Problem("an opening has two fillings");
      filling[rel->m_RelatingOpeningElement.get()] = rel->m_RelatedBuildingElement.get();
    }
    std::map<const void*, shared_ptr<IfcDoor>> doors;
    std::map<const void*, shared_ptr<IfcWindow>> windows;
    for (const auto& d : All<IfcDoor>()) doors[d.get()] = d;
    for (const auto& w : All<IfcWindow>()) windows[w.get()] = w;
    doors_ = static_cast<int>(doors.size());
    windows_ = static_cast<int>(windows.size());
    auto openings = All<IfcOpeningElement>();
    if (openings.size() != plan_.openings.size()) {
      Problem("read " + std::to_string(openings.size()) + " openings, plan.json has " +
              std::to_string(plan_.openings.size()));
    }
    int plan_doors = 0;
    for (const PlanOpening& o : plan_.openings) plan_doors += o.kind == OpeningKind::kDoor;
    if (doors_ != plan_doors || windows_ != static_cast<int>(plan_.openings.size()) - plan_doors) {
      Problem("read " + std::to_string(doors_) + " doors and " + std::to_string(windows_) + " windows, plan.json has " +
              std::to_string(plan_doors) + " and " + std::to_string(plan_.openings.size() - plan_doors));
    }
    for (const auto& opening : openings) {
      const void* fill = filling.count(opening.get()) ? filling[opening.get()] : nullptr;
      if (!fill) {
        Problem("an opening is not filled");
        continue;
      }
      const int i = Index(fill, "a door or window");
      if (i < 0 || i >= static_cast<int>(plan_.openings.size())) continue;
      const PlanOpening& po = plan_.openings[i];
      const std::string what = "openings[" + std::to_string(i) + "]";
      const bool door = doors.count(fill) > 0;
      if (door != (po.kind == OpeningKind::kDoor) || (!door && !windows.count(fill))) {
        Problem(what + ": filled by the wrong kind (plan.json: " + OpeningKindName(po.kind) + ")");
        continue;
      }
      const Sets& sets = sets_[fill];
      const void* wall = voided.count(opening.get()) ? voided[opening.get()] : nullptr;
      if (!wall || wall_by_index_[po.wall] != wall) Problem(what + ": does not void wall " + std::to_string(po.wall));
      if (Number(sets, "PlanWallIndex") != std::optional<double>(po.wall)) Problem(what + ": PlanWallIndex wrong");
      if (container_[fill] != storey_) Problem(what + ": its door/window is not contained in the storey");
      // The void's box: from the opening's start (placement origin) along the
      // wall (placement x) by the width, from the sill up by the height.
      const Isometry3d world = World(opening->m_ObjectPlacement);
      auto body = Body(opening);
      auto box = body ? std::dynamic_pointer_cast<IfcRectangleProfileDef>(body->m_SweptArea) : nullptr;
      if (!box) {
        Problem(what + ": the opening has no extruded rectangle 'Body'");
        continue;
      }
      const double width = box->m_XDim->m_value, height = body->m_Depth->m_value;
      const Vector3d start = world * Vector3d(0, 0, 0), end = world * Vector3d(width, 0, 0);
      Compare(what + " width", width, po.width);
      Compare(what + " centre x", 0.5 * (start.x() + end.x()), po.Centre().x());
      Compare(what + " centre y", 0.5 * (start.y() + end.y()), po.Centre().y());
      if (po.height) Compare(what + " height", height, *po.height);
      if (po.sill) Compare(what + " sill", start.z(), *po.sill);
      if (Boolean(sets, "HeightIsDefault") != std::optional<bool>(!po.height))
        Problem(what + ": HeightIsDefault wrong");
      if (Boolean(sets, "SillIsDefault") != std::optional<bool>(!po.sill)) Problem(what + ": SillIsDefault wrong");
      Compare(what + " Width", Number(sets, "Width").value_or(NAN), po.width);
      Compare(what + " Height", Number(sets, "Height").value_or(NAN), height);
      Compare(what + " Sill", Number(sets, "Sill").value_or(NAN), start.z());
      CompareOptional(what, sets, "WidthSigma", po.width_sigma_m);
      CompareOptional(what, sets, "HeightSigma", po.height_sigma_m);
      CompareOptional(what, sets, "SillSigma", po.sill_sigma_m);
      const double overall_width = door ? doors[fill]->m_OverallWidth->m_value : windows[fill]->m_OverallWidth->m_value;
      const double overall_height =
          door ? doors[fill]->m_OverallHeight->m_value : windows[fill]->m_OverallHeight->m_value;
      Compare(what + " OverallWidth", overall_width, po.width);
      Compare(what + " OverallHeight", overall_height, height);
      if (sets.qto_name != (door ? "Qto_DoorBaseQuantities" : "Qto_WindowBaseQuantities")) {
        Problem(what + ": no base quantities");
      }
    }
  }

  void CheckSpaces() {
    auto spaces = All<IfcSpace>();
    spaces_ = static_cast<int>(spaces.size());
    if (spaces.size() != plan_.rooms.size()) {
      Problem("read " + std::to_string(spaces.size()) + " spaces, plan.json has " + std::to_string(plan_.rooms.size()));
    }
    for (const auto& space : spaces) {
      const int i = Index(space.get(), "a space");
      if (i < 0 || i >= static_cast<int>(plan_.rooms.size())) continue;
      const PlanRoom& room = plan_.rooms[i];
      const std::string what = "rooms[" + std::to_string(i) + "]";
      if (parent_[space.get()] != storey_) Problem(what + ": the space is not aggregated into the storey");
      const Sets& sets = sets_[space.get()];
      Compare(what + " area", sets.quantities.count("NetFloorArea") ? sets.quantities.at("NetFloorArea") : NAN,
              room.area_m2);
      Compare(what + " Area", Number(sets, "Area").value_or(NAN), room.area_m2);
      CompareOptional(what, sets, "AreaSigma", room.area_sigma_m2);
      // The footprint: the room polygon (either orientation, closed).
      auto body = Body(space);
      auto profile = body ? std::dynamic_pointer_cast<IfcArbitraryClosedProfileDef>(body->m_SweptArea) : nullptr;
      std::vector<Vector3d> pts = profile ? PolylinePoints(profile->m_OuterCurve) : std::vector<Vector3d>{};
      const Isometry3d world = World(space->m_ObjectPlacement);
      std::vector<Vec2> polygon;
      for (const Vector3d& p : pts) polygon.push_back((world * p).head<2>());
      if (polygon.size() >= 2 && (polygon.front() - polygon.back()).norm() < kTolerance) polygon.pop_back();
      std::vector<Vec2> expected = room.polygon;
      if (expected.size() >= 2 && (expected.front() - expected.back()).norm() < kTolerance) expected.pop_back();
      if (polygon.size() != expected.size()) {
        Problem(what + ": the footprint has " + std::to_string(polygon.size()) + " corners, plan.json " +
                std::to_string(expected.size()));
        continue;
      }
      // Every plan corner is a footprint corner.
      for (size_t k = 0; k < expected.size(); ++k) {
        double nearest = INFINITY;
        for (const Vec2& p : polygon) nearest = std::min(nearest, (p - expected[k]).norm());
        Compare(what + " polygon[" + std::to_string(k) + "]", nearest, 0.0);
      }
      Compare(what + " footprint area", std::abs(PolygonArea(polygon)), std::abs(PolygonArea(expected)));
    }
  }

  const Plan& plan_;
  shared_ptr<BuildingModel> model_;
  std::vector<shared_ptr<BuildingEntity>> entities_;
  std::map<const void*, Sets> sets_;
  std::map<const void*, const void*> container_, parent_;
  std::map<int, const void*> wall_by_index_;
  const void *project_ = nullptr, *site_ = nullptr, *building_ = nullptr, *storey_ = nullptr;
  std::vector<std::string> problems_;
  double max_difference_ = 0;
  int walls_ = 0, doors_ = 0, windows_ = 0, spaces_ = 0;
};

void OnMessage(void* errors, shared_ptr<StatusCallback::Message> m) {
  if (m->m_message_type == StatusCallback::MESSAGE_TYPE_ERROR ||
      m->m_message_type == StatusCallback::MESSAGE_TYPE_WARNING) {
    static_cast<std::vector<std::string>*>(errors)->push_back(Narrow(m->m_message_text));
  }
}

}  // namespace
}  // namespace asbuilt

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: ifc_check PLAN.ifc PLAN.json\n");
    return 2;
  }
  try {
    asbuilt::Plan plan = asbuilt::ReadPlan(argv[2]);
    auto model = std::make_shared<BuildingModel>();
    ReaderSTEP reader;
    std::vector<std::string> messages;
    reader.setMessageCallBack(&messages, &asbuilt::OnMessage);
    // From a string: loadModelFromFile first tries setlocale("en-US"), which
    // fails (as an error message) on Linux.
    std::string content = asbuilt::ReadFile(argv[1]);
    reader.loadModelFromString(content, model);
    if (!messages.empty()) {
      for (const std::string& m : messages) std::printf("reader: %s\n", m.c_str());
      return 1;
    }
    if (model->getIfcSchemaVersion().m_ifc_file_schema_enum != BuildingModel::IFC4) {
      std::printf("problem: the file's schema is not IFC4\n");
      return 1;
    }
    return asbuilt::Checker(plan, model).Run();
  } catch (const std::exception& e) {
    std::printf("error: %s\n", e.what());
    return 2;
  }
}
