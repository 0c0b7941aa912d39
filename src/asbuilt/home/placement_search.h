#ifndef ASBUILT_HOME_PLACEMENT_SEARCH_H_
#define ASBUILT_HOME_PLACEMENT_SEARCH_H_

// The beam search that grows a home one link at a time (internal to home/;
// see home/placement.h): a state of rooms placed so far, the candidates
// that add one more room by a door link, and the Placer that expands,
// scores and keeps the best states.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "asbuilt/home/placement.h"
#include "asbuilt/home/placement_geometry.h"

namespace asbuilt::placement {

// Rooms placed so far, at which poses, by which links, and their score.
struct State {
  std::vector<char> placed;
  std::vector<Pose> pose;
  std::vector<int> link_of;             // Per room: index into links, -1.
  std::vector<std::vector<char>> used;  // Per room, per door (index into RoomGeom::doors).
  std::vector<RoomLink> links;
  double score = 0.0;
  int count = 0;
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);  // Bounding box in the home's axes.
  double covered_m2 = 0.0;                                       // Floor of the rooms placed.

  // Which rooms are where, to tell placements apart (centimetres, degrees).
  std::string Signature() const;
};

// Marks as used the doors of placed room `room` that meet a door of another
// placed room (a loop the home closes there), and those doors: a door seen
// from both sides links nothing else. `placed`: each room's geometry at its
// pose (nullptr: not placed).
void MarkMeetingDoors(const std::vector<const RoomGeom*>& placed, int room, const PlacementOptions& o, State& s);

// One more room placed from a state by one link.
struct Candidate {
  int from_state = 0;
  int a_room = 0, a_door = -1, b_room = 0, b_door = -1;  // Indices into RoomGeom::doors; −1: one-sided.
  int a_wall = -1, b_wall = -1;                          // A one-sided link's plain wall.
  Pose pose = Pose::Identity();
  double score = 0.0;
  bool by_user = false;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // The home's box with the room.
};

// The beam search over one home's rooms; its caches live as long as it.
class Placer {
 public:
  Placer(const std::vector<HomeRoomInput>& rooms, const PlacementOptions& options,
         const PlacementConstraints& constraints);

  // Beam search from `seed`; every complete or stuck placement, best first.
  // Door-to-door links first; then, from the best of those placements, the
  // rooms left over by one-sided links too (a door one survey missed). A
  // room one-sided links could place wrongly never displaces a door link.
  std::vector<State> Search(int seed, const Pose& seed_pose);

  // The state with `seed` at `seed_pose` and the rooms a person fixed.
  State Start(int seed, const Pose& seed_pose);

  // Grows every state one room at a time, keeping the best beam_width;
  // every state that cannot grow, best first.
  std::vector<State> Beam(std::vector<State> beam);

  const std::vector<RoomGeom>& geoms() const { return geoms_; }

 private:
  // Whether a person said the two openings are not / are one door.
  bool Forbidden(const OpeningRef& x, const OpeningRef& y) const;
  bool AskedFor(const OpeningRef& x, const OpeningRef& y) const;

  // A room's geometry at a pose, computed once per room and pose (to 0.1 mm
  // and 1e-6 rad).
  const RoomGeom& PlacedGeom(int room, const Pose& pose);

  // Every room placed by one more link from `s` (the state's index), scored.
  std::vector<Candidate> Expand(const State& s, int index);

  // The terms of `room` at `pose` against the rooms `s` placed; nullopt when refused.
  std::optional<double> Score(const State& s, int room, const Pose& pose);

  // `from` with the candidate's room placed.
  State Apply(const State& from, const Candidate& c);

  const std::vector<HomeRoomInput>& rooms_;
  const PlacementOptions& o_;
  const PlacementConstraints& c_;
  std::vector<RoomGeom> geoms_;
  struct PoseKey {
    int room;
    long long x, y, yaw;
    bool operator==(const PoseKey&) const = default;
  };
  struct PoseKeyHash {
    std::size_t operator()(const PoseKey& k) const {
      std::size_t h = std::hash<long long>()(k.x);
      for (long long v : {k.y, k.yaw, static_cast<long long>(k.room)}) h = h * 1000003u ^ std::hash<long long>()(v);
      return h;
    }
  };
  static PoseKey KeyOf(int room, const Pose& pose);
  std::unordered_map<PoseKey, RoomGeom, PoseKeyHash> placed_cache_;
  // PairScore of two rooms at two poses: the beam's states share most of
  // their rooms, so most pairs are scored again and again.
  struct PairKeyHash {
    std::size_t operator()(const std::pair<PoseKey, PoseKey>& k) const {
      return PoseKeyHash()(k.first) * 1000003u ^ PoseKeyHash()(k.second);
    }
  };
  std::unordered_map<std::pair<PoseKey, PoseKey>, std::optional<double>, PairKeyHash> pair_cache_;
  std::vector<const RoomGeom*> placed_now_;  // The expanded state's placed rooms (nullptr: not placed).
  Eigen::Matrix2d axes_ = Eigen::Matrix2d::Identity();
  bool one_sided_ = false;
  int width_ = 0;  // The beam's width now.
};

}  // namespace asbuilt::placement

#endif  // ASBUILT_HOME_PLACEMENT_SEARCH_H_
