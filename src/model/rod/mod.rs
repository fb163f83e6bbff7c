//! The Cosserat director rod of the paper, whole: the element (strains,
//! energy, internal force and tangent, [`element`], [`gauss`]), the assembled
//! line ([`mod@line`]), its mass ([`mass`]), static equations ([`statics`]), step
//! equations (`step`), the dynamic model ([`dynamic`]) and its outputs.

pub mod dofs;
pub mod dynamic;
pub mod element;
pub mod gauss;
pub mod joint;
pub mod line;
pub mod linearized;
pub mod mass;
pub mod outputs;
pub mod statics;
mod step;

pub use dynamic::RodModel;
pub use joint::{FlexJoint, JointLaw};
pub use line::{EndBc, Rod, RotationBc, Stiffness};
pub use step::RodWorkspace;

use crate::model::sections::PerElement;
use crate::scene::Scene;
use crate::scene::sections::LineProperties;

/// The rod of a scene: its mesh, the stiffness of its sections and end
/// conditions (pinned hang-off, pinned anchor with the twist held).
pub fn of_scene(scene: &Scene) -> Rod {
    of_properties(scene, &crate::model::sections::element_properties(scene))
}

/// The rod of a scene whose element properties `props` are at hand.
pub fn of_properties(scene: &Scene, props: &PerElement<LineProperties>) -> Rod {
    let stiffness: Vec<Stiffness> = (0..scene.analysis.n_elements)
        .map(|e| {
            let p = props.at(e);
            Stiffness::paper(p.axial_stiffness, p.bending_stiffness, p.torsional_stiffness)
        })
        .collect();
    let mut rod =
        Rod::new(scene.analysis.n_elements, scene.line.length, stiffness[0], [EndBc::PINNED, EndBc::PINNED_NO_TWIST]);
    rod.set_element_stiffness(&stiffness);
    rod
}
