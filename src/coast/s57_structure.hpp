#pragma once
/// The S-57 structure classes, shared by the coastline import (structures as hazards) and
/// the expected-contact areas (structures as the place a contact point lies on): which object
/// classes they are, the kind of one feature from its category attribute, and a feature's
/// name. Internal.

#include <ogrsf_frmts.h>

#include <string>

#include <shoal/coast/coastline.hpp>

namespace shoal::coast::s57 {

/// Whether the S-57 object class `name` (any case) is a structure class: SLCONS, PONTON,
/// HULKES or MORFAC.
bool is_structure_class(const std::string& name);

/// The fields a structure's kind and name are read from, found once per layer.
struct StructureFields {
    std::string object_class;  ///< the class, upper case
    int category = -1;         ///< CATSLC (SLCONS) or CATMOR (MORFAC), any case; -1: none
    int objnam = -1;           ///< OBJNAM, any case
    int name = -1;             ///< "name", any case
};
StructureFields structure_fields(const std::string& object_class, const OGRFeatureDefn& defn);

/// The kind of one feature of a structure class (coast::StructureKind), from its class and
/// category: an Integer as GDAL's S-57 driver gives it, an IntegerList (the first value
/// counts), or text ("4", "4,6", or the kind's name itself, as other converters write it).
/// No value or an unknown one: shoreline_construction (SLCONS), mooring_facility (MORFAC).
StructureKind structure_kind(const StructureFields& fields, const OGRFeature& f);

/// The feature's OBJNAM, else its attribute called "name"; "" when neither is set.
std::string feature_name(const StructureFields& fields, const OGRFeature& f);

/// Index of the first field called `name` (upper case) in any case, or -1.
int field_index(const OGRFeatureDefn& defn, const std::string& name);

}  // namespace shoal::coast::s57
