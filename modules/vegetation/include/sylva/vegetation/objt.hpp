#pragma once
// The OBJT tree format of seed 000 §4.3.1 (extraction §3.1): a text file with a name record, branch
// blocks, leaf blocks and // line comments, all coordinates in the tree's object space.
//
//   name = "oak"
//   B 3 {                 // branch identifier
//       l 1               // level in the hierarchy (0 = trunk)
//       d 4.5             // length
//       z 0 2.5 0         // start point
//       k 3.1 5.7 0.2     // end point
//       r ... s ... t ... // frame; t along the branch, r x s = t
//       p 0               // parent branch identifier (negative for a root)
//       x 0.25            // where on the parent the branch starts, [0, 1]
//   }
//   L 7 { r ... s ... t ... p 3 x 0.9 }   (one field per line, as branches)
//
// The seed's format has no radii, leaf sizes or per-leaf numbers (extraction §3.1 notes). Sylva
// adds optional fields so a model round-trips exactly; files without them load with defaults:
//   branch  w <radius_base> <radius_tip>   default: 0.03 d at the base, taper 0.2 (the taper the
//                                          seed's constants belong to); ObjtReadOptions changes both
//   branch  c <c2> <c4>                    default: fitted from the taper (bending.hpp)
//   leaf    w <width> <length>             default: 0.05 x 0.08 (ObjtReadOptions)
//   leaf    n <number in [0, 1)>           default: a hash of the leaf id and the seed
//   header  seed = <uint32>                default: 0; seeds the per-branch noise signals
// Leaf frame vectors: r is the leaf normal n, s the bitangent b = t x n, t the blade axis.
//
// Grammar details: a block opens with "B <id> {" or "B <id>" followed by a line "{", and closes
// with a line "}". "name" must come before the first block. Fields may appear in any order, each
// exactly once. Identifiers are integers, unique per kind; they need not be contiguous.
//
// Checks (every error names the source, the line and the field or record):
//  - syntax: unknown record or field, wrong number of values, non-numeric values, unterminated
//    block, duplicate field, missing required field (named, with the block's line);
//  - references: duplicate identifiers, a parent that does not exist, cycles in the parent links
//    (the cycle is listed), more than kMaxLevels levels (kLimit);
//  - values: non-finite numbers, d < 0, x outside [0, 1], negative radii, non-positive leaf sizes,
//    zero or parallel frame vectors.
// Files as the seed wrote them load (issue #16): what the seed leaves open or what its own tools
// may have written is repaired, each with a warning "file:line: ..." that says what was done:
//  - a branch naming itself as its parent (the seed leaves the trunk's p open) is a root;
//  - a level `l` that does not match the parent chain takes the chain's level;
//  - an end point `k` more than 1 mm + 1 % of d away from z + d t is ignored (the end is z + d t:
//    the animation uses the frame and the length);
//  - a frame that is not orthonormal and right-handed within 1e-5 is re-orthonormalised keeping t
//    and the direction of r (a left-handed frame gets s = t x r).
// ObjtReadOptions::strict turns the first three and left-handed frames into errors instead.

#include <sylva/core/result.hpp>
#include <sylva/vegetation/tree_model.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::vegetation {

struct ObjtReadOptions {
  std::string source_name = "<objt>";  // used in messages (load_objt sets the file name)
  float max_length_error = 0.009f;     // bound for the branch amplitude limits (bending.hpp)
  bool strict = false;                 // refuse what is otherwise repaired with a warning (above)
  // Where repair warnings go ("file:line: ..."); not owned; null = the log (log_warn).
  std::vector<std::string>* warnings = nullptr;
  // Rules for files without the Sylva extensions (a species file sets them, species_file.hpp):
  // a branch without 'w' gets radius_base = default_radius_ratio * d and radius_tip =
  // default_taper * radius_base; a leaf without 'w' gets this size (file units).
  float default_radius_ratio = 0.03f;
  float default_taper = 0.2f;
  float default_leaf_width = 0.05f;
  float default_leaf_length = 0.08f;
};

Result<TreeModel> parse_objt(std::string_view text, const ObjtReadOptions& options = {});
// Reads the file (kNotFound / kIo) and parses it.
Result<TreeModel> load_objt(const std::filesystem::path& path, ObjtReadOptions options = {});

// Writes every field, the Sylva extensions included, with shortest round-trip float formatting,
// so parse_objt(format_objt(m)) reproduces m exactly (m must pass validate()).
std::string format_objt(const TreeModel& model);
// Atomic write (a failed save never destroys an existing file).
Status save_objt(const std::filesystem::path& path, const TreeModel& model);

}  // namespace sylva::vegetation
