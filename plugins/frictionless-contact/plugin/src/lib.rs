//! Exports the `frictionless-contact` law through the Stiction law ABI (`stiction_law_descriptor`).
stiction_law_sdk::export_law!(stiction_law_frictionless_contact::FrictionlessContact);
