// Contacts: a model frame that does not move. A `point` contact holds the frame's origin (3 rows: its
// linear acceleration is zero, the wrench a force at the origin); a `surface` contact holds the
// whole frame (6 rows: angular then linear acceleration zero, the wrench a moment and a force). Rows
// and wrenches are in the contact frame's axes, about its origin. An optional friction coefficient μ
// is checked, not enforced: the contact frame's z axis is the surface normal.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

enum class ContactKind { Point, Surface };

/// "point" or "surface"; anything else throws std::invalid_argument naming it.
inline ContactKind parse_contact_kind(const std::string& kind, const std::string& frame) {
  if (kind == "point") return ContactKind::Point;
  if (kind == "surface") return ContactKind::Surface;
  throw std::invalid_argument("contact '" + frame + "': unknown kind '" + kind + "' (point or surface)");
}

inline const char* contact_kind_name(ContactKind kind) { return kind == ContactKind::Point ? "point" : "surface"; }

/// The number of constraint rows of a kind: 3 or 6.
inline int contact_rows(ContactKind kind) { return kind == ContactKind::Point ? 3 : 6; }

template <class S>
struct Contact {
  std::string frame_name;
  int frame = -1;  // index into model.frames
  ContactKind kind = ContactKind::Point;
  S friction = S(0);  // μ; 0: no cone to check
  int row = 0;        // first row in the stacked constraint
};

/// The contacts of one call, validated against a model; rows stacked in the given order.
template <class S>
struct ContactSet {
  std::vector<Contact<S>> contacts;
  int rows = 0;

  ContactSet() = default;

  /// Frames, kinds and (empty, or one per contact) friction coefficients. An unknown frame or kind, a
  /// frame named twice, mismatched lengths or a negative or non-finite μ throw std::invalid_argument
  /// naming it.
  ContactSet(const Model<S>& model, const std::vector<std::string>& frames, const std::vector<std::string>& kinds,
             const std::vector<S>& frictions = {}) {
    if (kinds.size() != frames.size())
      throw std::invalid_argument("contacts: " + std::to_string(frames.size()) + " frames but " +
                                  std::to_string(kinds.size()) + " kinds");
    if (!frictions.empty() && frictions.size() != frames.size())
      throw std::invalid_argument("contacts: " + std::to_string(frames.size()) + " frames but " +
                                  std::to_string(frictions.size()) + " friction coefficients");
    for (std::size_t k = 0; k < frames.size(); ++k) {
      Contact<S> contact;
      contact.frame_name = frames[k];
      if (!model.hasFrame(frames[k])) throw std::invalid_argument("contact: unknown frame '" + frames[k] + "'");
      contact.frame = model.frameIndex(frames[k]);
      for (const Contact<S>& other : contacts)
        if (other.frame == contact.frame) throw std::invalid_argument("contact: frame '" + frames[k] + "' is named twice");
      contact.kind = parse_contact_kind(kinds[k], frames[k]);
      if (!frictions.empty()) {
        using std::isfinite;
        if (!(frictions[k] >= S(0)) || !isfinite(static_cast<double>(frictions[k])))
          throw std::invalid_argument("contact '" + frames[k] + "': the friction coefficient must be finite and >= 0");
        contact.friction = frictions[k];
      }
      contact.row = rows;
      rows += contact_rows(contact.kind);
      contacts.push_back(contact);
    }
  }

  bool empty() const { return contacts.empty(); }
  std::size_t size() const { return contacts.size(); }
};

}  // namespace spatial_dynamics
