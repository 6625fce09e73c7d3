//! The component sets and the unknown numbering.

use super::*;

/// Component sets and the unknown numbering.
#[test]
fn component_sets_and_dof_layout() {
    assert_eq!("x".parse::<ComponentSet>().unwrap(), ComponentSet::One(0));
    assert_eq!(" Z ".parse::<ComponentSet>().unwrap(), ComponentSet::One(2));
    assert_eq!("all".parse::<ComponentSet>().unwrap(), ComponentSet::All);
    match "xy".parse::<ComponentSet>() {
        Err(e @ FieldError::UnknownComponent { .. }) => {
            assert!(e.to_string().contains("x, y, z or all"))
        }
        other => panic!("expected UnknownComponent, got {other:?}"),
    }
    assert_eq!(ComponentSet::One(1).to_string(), "y");
    let layout = DofLayout::new(4, 3);
    assert_eq!(layout.len(), 12);
    assert_eq!(layout.dof(2, 1), 7);
    assert_eq!(layout.node_component(7), (2, 1));
    assert_eq!(
        layout.expand_nodes(&[3, 0], ComponentSet::All).unwrap(),
        vec![9, 10, 11, 0, 1, 2]
    );
    assert_eq!(
        layout.expand_nodes(&[1, 2], ComponentSet::One(2)).unwrap(),
        vec![5, 8]
    );
    assert!(matches!(
        layout.expand_nodes(&[4], ComponentSet::All),
        Err(FieldError::NodeBeyondLayout { node: 4, nodes: 4 })
    ));
    assert!(matches!(
        layout.expand_nodes(&[0], ComponentSet::One(3)),
        Err(FieldError::NoSuchComponent {
            component: 3,
            components: 3,
            ..
        })
    ));
    let scalar = DofLayout::new(5, 1);
    assert_eq!(
        scalar.expand_nodes(&[4, 2], ComponentSet::All).unwrap(),
        vec![4, 2]
    );
}
