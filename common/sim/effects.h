#pragma once
// Effects: the stages of a simulation step. A stage runs only when the
// scene enables it AND some consumer needs its output (or the output of a
// stage that depends on it): a scene whose clients only ask "colliding?"
// never reconstructs contacts.

#include <cstdint>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"

namespace hs {

enum class Effect : uint8_t {
  kCollision,            ///< Which tool-object pairs touch or penetrate (yes/no).
  kContactSet,           ///< Features, points, normal, depth and reversing vector per pair.
  kReversingVector,      ///< The tool's reversing vector: its proxy pose, kept out of objects.
  kForce,                ///< Spring-damper force and torque on each tool.
  kFriction,             ///< Coulomb friction in the proxy's sliding.
  kContinuousCollision,  ///< Contact anywhere along the step, not only at its end.
  kFreeBodyMotion,       ///< Free objects move under the simulation.
  kLocalModel,           ///< Each tool's local contact model, for remote devices.
};
inline constexpr int kNumEffects = 8;

/// A set of effects (a bit mask).
class EffectSet {
 public:
  constexpr EffectSet() = default;
  constexpr EffectSet(std::initializer_list<Effect> effects) {
    for (Effect e : effects) bits_ |= Bit(e);
  }
  static constexpr EffectSet All() { return EffectSet((1u << kNumEffects) - 1); }
  /// What a consumer that names no needs gets: every effect but the local
  /// model, which only remote devices use and ask for by name (it costs a
  /// face search per tool and step).
  static constexpr EffectSet Default() { return All().Without(Effect::kLocalModel); }

  constexpr bool Has(Effect e) const { return (bits_ & Bit(e)) != 0; }
  constexpr EffectSet With(Effect e) const { return EffectSet(bits_ | Bit(e)); }
  constexpr EffectSet Without(Effect e) const { return EffectSet(bits_ & ~Bit(e)); }
  constexpr EffectSet operator&(EffectSet o) const { return EffectSet(bits_ & o.bits_); }
  constexpr EffectSet operator|(EffectSet o) const { return EffectSet(bits_ | o.bits_); }
  constexpr bool operator==(const EffectSet&) const = default;
  constexpr uint32_t bits() const { return bits_; }

 private:
  constexpr explicit EffectSet(uint32_t bits) : bits_(bits) {}
  static constexpr uint32_t Bit(Effect e) { return 1u << static_cast<int>(e); }
  uint32_t bits_ = 0;
};

/// `needed` plus every effect those need to have run first: friction needs
/// force, which needs the reversing vector (the proxy, which reads no other
/// stage), as the local model does; the contact set and continuous
/// collision need collision.
EffectSet WithPrerequisites(EffectSet needed);

/// The stages a step runs: what the scene enables, of what consumers need
/// (with prerequisites). A needed stage whose prerequisite is disabled does
/// not run. Continuous collision is a way of computing collision, so it runs
/// whenever collision does and the scene enables it.
EffectSet StagesToRun(EffectSet enabled, EffectSet needed);

/// "collision", "contact_set", "reversing_vector", "force", "friction",
/// "continuous_collision", "free_body_motion", "local_model".
std::string_view EffectName(Effect effect);
/// The names of the effects in `effects`, in Effect order.
std::vector<std::string_view> EffectNames(EffectSet effects);
/// The inverse of EffectName; INVALID_ARGUMENT for any other text.
absl::StatusOr<Effect> ParseEffect(std::string_view name);

}  // namespace hs
