// A bounding-volume tree over a shot's possible receivers (patches on their own and
// face clusters), for culling what a sender cannot see before any form factor is
// computed.
//
// A shot from a wall of one room reaches that room and what its doors and windows
// show; the other rooms, storeys and the outside of the building are behind walls.
// Cells and portals (Teller & Hanrahan 1993) find that from rooms; this finds it from
// the geometry alone, as hierarchical radiosity's cluster links do: a node of the tree
// far enough from the sender is tested with a few rays from points on its receivers
// to the sender, and a node none of whose facing points sees the sender is culled
// with everything below it. A node whose points all see the sender is taken whole
// (its children are not tested again); one that is partly seen is opened and its
// children are tested in turn. Small nodes (fewer than kMinTested receivers) and nodes
// near the sender are never tested: their receivers' own rays decide.
//
// A test can miss what a node shows through a gap narrower than its points are apart
// (a node of which a twentieth is seen, through a door, is culled by 32 points with a
// chance of about a fifth). The shot's power then went to the receivers that were kept
// (the shot's normalisation, see shoot.cpp), and that was not local: in nine offices
// joined by doors, path-traced, the middle office's indirect light came out 4.3% low and
// the corners' 1.2-1.5% (all about 1.4% with no culling). So the sender's own rays say
// what it sees too (Visit's `kept`): a node one of them meets is not culled.
#pragma once

#include "mesh/core/types.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace dynrad::rad {

class ReceiverTree {
 public:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  static constexpr std::uint32_t kMinTested = 48;   // receivers below a node worth a test
  static constexpr std::uint32_t kSamples = 32;     // points per tested node
  static constexpr std::uint32_t kLeafSize = 8;

  // A point on a receiver's surface with its normal and the area it stands for.
  struct Piece {
    Vec3d point, normal;
    double area = 0;
  };
  struct Item {
    Bounds bounds;
    std::vector<Piece> pieces;
  };
  struct Node {
    Bounds bounds;
    std::uint32_t first = 0, count = 0;  // into order()
    std::uint32_t children[2] = {kNone, kNone};
    std::uint32_t first_sample = 0, sample_count = 0;
    bool leaf() const { return children[0] == kNone; }
  };

  ReceiverTree() = default;
  explicit ReceiverTree(const std::vector<Item>& items);

  bool empty() const { return nodes_.empty(); }
  const Node& node(std::uint32_t n) const { return nodes_[n]; }
  const Piece& sample(std::uint32_t s) const { return samples_[s]; }
  // Items in tree order: node n holds order()[first .. first + count).
  const std::vector<std::uint32_t>& order() const { return order_; }

  // What a test said of a node.
  enum class Seen { hidden, partly, wholly, untested };
  // The items a sender may reach, in tree order. `near(bounds)`: the sender is near or
  // inside the box (no test). `test(node)`: counts the node's facing samples that see
  // the sender (called in parallel, must be thread-safe and deterministic per node).
  struct Visit {
    std::vector<std::uint32_t> items;
    std::size_t culled_nodes = 0, culled_items = 0, tests = 0;
  };
  // `kept`, when given: positions in order() (sorted) of items the sender is known to
  // see (its own rays met them): a node holding one is never culled, whatever its test
  // says (a room seen through a door, which a node's points may all miss).
  Visit visit(const std::function<bool(const Bounds&)>& near, const std::function<Seen(std::uint32_t node)>& test,
              const std::vector<std::uint32_t>* kept = nullptr) const;
  // Where item i stands in order().
  std::uint32_t position(std::uint32_t item) const { return position_[item]; }

 private:
  std::uint32_t build(std::vector<std::uint32_t>& ids, std::uint32_t begin, std::uint32_t end,
                      const std::vector<Item>& items, const std::vector<Vec3d>& centres);
  void add_samples(Node& node, const std::vector<Item>& items);
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
  std::vector<Piece> samples_;
  std::vector<std::uint32_t> position_;  // per item, its index in order_
};

}  // namespace dynrad::rad
