# Layer: input. Modules and the objects of the modules each one uses.
# deck_*_cards and deck_model_checks are submodules of deck_parser: each
# object needs the parent's (gfortran writes the parent's .smod with its
# .mod). file_kind is a C shim (stat), see file_kind.c.
MODULES += file_kind deck_input model_growth deck_cursor deck_parser deck_mesh_cards deck_material_cards \
           deck_step_cards deck_contact_cards deck_model_checks deck_interaction_cards deck_compat_cards deck_load_cards \
           deck_constraint_cards deck_part_cards deck_rigid_cards deck_heat_cards deck_coupled_cards
$(OBJDIR)/file_kind.o:
$(OBJDIR)/deck_input.o: $(OBJDIR)/growable.o $(OBJDIR)/messages.o $(OBJDIR)/strings.o
$(OBJDIR)/model_growth.o: $(OBJDIR)/growable.o $(OBJDIR)/model.o
$(OBJDIR)/deck_cursor.o: $(OBJDIR)/deck_input.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_parser.o: $(OBJDIR)/deck_coupled_cards.o $(OBJDIR)/deck_heat_cards.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_mesh_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_material_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/small_matrices.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_step_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_contact_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/solver_codes.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_model_checks.o: $(OBJDIR)/constraints.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/deck_parser.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/mesh_topology.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_interaction_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/kinds.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_compat_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_load_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_constraint_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_part_cards.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_rigid_cards.o: $(OBJDIR)/constraints.o $(OBJDIR)/deck_parser.o $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/growable.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/model_growth.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_heat_cards.o: $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_input.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/deck_coupled_cards.o: $(OBJDIR)/deck_cursor.o $(OBJDIR)/deck_heat_cards.o $(OBJDIR)/deck_input.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
