//! The joint types of the URDF specification, with their names and degrees of freedom.

use std::fmt;

/// The joint types of the URDF specification.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// Rotation about the axis, between limits.
    Revolute,
    /// Rotation about the axis, unlimited.
    Continuous,
    /// Translation along the axis.
    Prismatic,
    /// No motion: the child is rigidly attached (merged into the parent's body by [`crate::merge`]).
    Fixed,
    /// Six degrees of freedom.
    Floating,
    /// Translation in the plane normal to the axis, and rotation about the axis (three degrees of freedom).
    Planar,
}

impl JointKind {
    /// The kind named by a URDF `type` attribute (exact, lower case as the specification writes them).
    pub fn from_urdf(text: &str) -> Option<JointKind> {
        Some(match text {
            "revolute" => JointKind::Revolute,
            "continuous" => JointKind::Continuous,
            "prismatic" => JointKind::Prismatic,
            "fixed" => JointKind::Fixed,
            "floating" => JointKind::Floating,
            "planar" => JointKind::Planar,
            _ => return None,
        })
    }

    /// The URDF name of the type.
    pub fn as_str(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
            JointKind::Floating => "floating",
            JointKind::Planar => "planar",
        }
    }

    /// How many coordinates the joint adds: 1 (revolute, continuous, prismatic), 3 (planar), 6 (floating), 0 (fixed).
    pub fn degrees_of_freedom(self) -> usize {
        match self {
            JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic => 1,
            JointKind::Planar => 3,
            JointKind::Floating => 6,
            JointKind::Fixed => 0,
        }
    }

    /// Whether the joint's `<axis>` means something (all but fixed and floating).
    pub fn uses_axis(self) -> bool {
        !matches!(self, JointKind::Fixed | JointKind::Floating)
    }
}

impl fmt::Display for JointKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}
