#pragma once
// L-systems for plants (seed 004 §4): the seed's file format, stochastic derivation with a salt
// and a hard cap on the expanded length.
//
// File format (seed §4.5.1), several systems per file, one after another:
//     yaw_angle pitch_angle shrink_ratio      three numbers: degrees, degrees, (0, 1]
//     axiom
//     letter > production                      any number of rules
//     # comment                                 only on its own line
// Blank lines are skipped. Whitespace inside an axiom or production is ignored (the seed's acacia
// writes `E > x [++++UE1S&F+F+F+F] +UE`). Symbols are printable ASCII except whitespace, '#' and
// '>' (the rule separator); '[' and ']' must balance within every axiom and production, so every
// derived string is balanced. A new system starts at the next line holding three numbers.
// Errors name "<source>:<line>:<column>" (1-based) and what was expected.
//
// Stochastic rules (seed §4.4): a letter with n rules rewrites with each with probability 1/n,
// chosen independently for every occurrence; repeating a rule weights it (the seed's footnote 5).

#include <sylva/core/result.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::voxel {

struct LSystemRule {
  char letter = 0;
  std::string production;  // whitespace removed
  int line = 0;            // 1-based line in the source
};

struct LSystem {
  float yaw_angle = 0.0f;     // degrees turned by '+' and '-' (about world y)
  float pitch_angle = 0.0f;   // degrees turned by '^' and '&' (about the turtle's right axis)
  float shrink_ratio = 1.0f;  // 'x' multiplies the block size by it, 'X' divides, in (0, 1]
  std::string axiom;
  std::vector<LSystemRule> rules;  // file order
  std::string source;              // file name (or label) it was parsed from
  int line = 0;                    // line of its header

  // Indices into `rules` of the rules for one letter (empty: the letter is copied unchanged).
  const std::vector<int>& rules_for(char letter) const { return by_letter_[static_cast<unsigned char>(letter) & 127u]; }
  // Rebuilds the per-letter table; call after editing `rules` by hand.
  void index_rules();
  // "<source>:<line>" for messages.
  std::string where() const;

 private:
  std::array<std::vector<int>, 128> by_letter_{};
};

// Parses every system in `text`; `source` names the file in error messages.
Result<std::vector<LSystem>> parse_lsystems(std::string_view text, std::string_view source);
// Reads and parses a file (kNotFound / kIo naming the path, or the parse error).
Result<std::vector<LSystem>> load_lsystems(const std::filesystem::path& path);

// Grammar files shipped in modules/voxel/data/, embedded into the binary at build time so a
// player never depends on the working directory. Names as in the folder, e.g. "acacia.lsys".
std::vector<std::string> builtin_lsystem_files();
// kNotFound naming the file and the available ones.
Result<std::vector<LSystem>> load_builtin_lsystems(std::string_view file_name);

struct ExpansionLimits {
  std::size_t max_symbols = std::size_t{1} << 21;  // longest derived string
  std::size_t max_parts = 200'000;                 // most blocks one plant may place
  std::size_t max_depth = 4096;                    // deepest '[' nesting during interpretation
};

// Applies `derivations` parallel rewriting steps to the axiom. Rule choice is drawn from a PCG32
// stream seeded by `salt`, so the same (system, derivations, salt) always gives the same string.
// kLimit (naming the system, the step and the cap) instead of growing past max_symbols.
Result<std::string> derive(const LSystem& system, int derivations, std::uint64_t salt,
                           const ExpansionLimits& limits = {});

}  // namespace sylva::voxel
