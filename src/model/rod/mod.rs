//! The Cosserat director rod of the paper, whole: the element (strains,
//! energy, internal force and tangent, [`element`], [`gauss`]), the assembled
//! line ([`mod@line`]), its mass ([`mass`]), static equations ([`statics`]), step
//! equations (`step`), the dynamic model ([`dynamic`]) and its outputs.

pub mod dofs;
pub mod dynamic;
pub mod element;
pub mod gauss;
pub mod line;
pub mod linearized;
pub mod mass;
pub mod outputs;
pub mod statics;
mod step;

pub use dynamic::RodModel;
pub use line::{EndBc, Rod, RotationBc, Stiffness};
pub use step::RodWorkspace;

use crate::scene::Scene;

/// The rod of a scene: its mesh, the stiffness of its sections and end
/// conditions (pinned hang-off, pinned anchor with the twist held).
pub fn of_scene(scene: &Scene) -> Rod {
    let mut rod = Rod::new(
        scene.analysis.n_elements,
        scene.line.length,
        stiffness_of_scene(scene),
        [EndBc::PINNED, EndBc::PINNED_NO_TWIST],
    );
    if !scene.section.is_empty() {
        let props = crate::model::sections::element_properties(scene);
        rod.set_element_stiffness(&dynamic::element_stiffness(&props, rod.n_el));
    }
    rod
}

/// The section stiffness of a scene's `[line]`.
pub fn stiffness_of_scene(scene: &Scene) -> Stiffness {
    Stiffness::paper(scene.line.axial_stiffness, scene.line.bending_stiffness, scene.line.torsional_stiffness)
}
